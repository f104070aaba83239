/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * floor - the cost any HAL dispatcher pays on this CPU, in time-stamp-counter
 * clocks per function, for bench/hal/run.sh:
 *   loop    1000 indirect calls of an and2-like function from a contiguous
 *           table (an empty dispatch loop: the function's own cost);
 *   timed   the same with one time-stamp-counter read after each call and
 *           LinuxCNC's .time/.tmax/.tmax-increased bookkeeping (the least a
 *           dispatcher that times every function every period can cost);
 *   rdtsc   one time-stamp-counter read alone.
 * Best of many runs, so the figures are the machine's, not its noise.
 */
#include <stdint.h>
#include <stdio.h>

#define N 1000

static inline uint64_t tsc(void)
{
    unsigned int lo, hi;
    __asm__ __volatile__("rdtsc" : "=a"(lo), "=d"(hi));
    return ((uint64_t)hi << 32) | lo;
}

typedef struct {
    volatile _Bool *in0, *in1, *out;
} and2_t;

__attribute__((noinline)) static void and2(void *arg, long period)
{
    and2_t *a = arg;
    (void)period;
    *a->out = *a->in0 && *a->in1;
}

typedef struct {
    int32_t *runtime;
    int32_t maxtime;
    _Bool increased;
} store_t;

typedef struct {
    void (*f)(void *, long);
    void *arg;
    store_t *st;
} entry_t;

int main(void)
{
    static volatile _Bool bits[3 * N];
    static and2_t a[N];
    static store_t st[N];
    static int32_t times[N];
    static entry_t e[N];
    for (int i = 0; i < N; i++) {
        a[i] = (and2_t){&bits[3 * i], &bits[3 * i + 1], &bits[3 * i + 2]};
        st[i].runtime = &times[i];
        e[i] = (entry_t){and2, &a[i], &st[i]};
    }
    uint64_t best_loop = UINT64_MAX, best_timed = UINT64_MAX, best_tsc = UINT64_MAX;
    for (int rep = 0; rep < 3000; rep++) {
        uint64_t t0 = tsc();
        for (entry_t *p = e; p < e + N; p++)
            p->f(p->arg, 100000);
        uint64_t t1 = tsc();
        if (t1 - t0 < best_loop)
            best_loop = t1 - t0;
        t0 = tsc();
        uint64_t start = t0;
        for (entry_t *p = e; p < e + N; p++) {
            p->f(p->arg, 100000);
            uint64_t now = tsc();
            int32_t dt = (int32_t)(now - start);
            start = now;
            *p->st->runtime = dt;
            int inc = dt > p->st->maxtime;
            if (inc)
                p->st->maxtime = dt;
            p->st->increased = inc;
        }
        t1 = tsc();
        if (t1 - t0 < best_timed)
            best_timed = t1 - t0;
        t0 = tsc();
        for (int i = 0; i < N; i++)
            (void)tsc();
        t1 = tsc();
        if (t1 - t0 < best_tsc)
            best_tsc = t1 - t0;
    }
    printf("%.2f %.2f %.2f\n", (double)best_loop / N, (double)best_timed / N, (double)best_tsc / N);
    return 0;
}
