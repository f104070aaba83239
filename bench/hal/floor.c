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
 * Then the same "timed" loop and the read alone with the two ordered
 * variants a dispatcher could use instead of plain rdtsc (x86 only):
 *   rdtscp        waits until every earlier instruction has executed, so
 *                 a function's tail is not counted in the next one's time;
 *   lfence;rdtsc  the same ordering through a load fence.
 * Output: loop timed rdtsc timed_rdtscp timed_lfence rdtscp lfence_rdtsc
 * (clocks per function / per read).  Best of many runs, so the figures are
 * the machine's, not its noise.
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

static inline uint64_t tscp(void)
{
    unsigned int lo, hi, aux;
    __asm__ __volatile__("rdtscp" : "=a"(lo), "=d"(hi), "=c"(aux));
    return ((uint64_t)hi << 32) | lo;
}

static inline uint64_t tscf(void)
{
    unsigned int lo, hi;
    __asm__ __volatile__("lfence\n\trdtsc" : "=a"(lo), "=d"(hi)::"memory");
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

/* One timed pass over the table with the time stamp READ(); clocks. */
#define TIMED_PASS(READ, e, best)                                                                \
    do {                                                                                       \
        uint64_t t0_ = tsc(), start_ = READ();                                                 \
        for (entry_t *p = (e); p < (e) + N; p++) {                                             \
            p->f(p->arg, 100000);                                                              \
            uint64_t now_ = READ();                                                            \
            int32_t dt_ = (int32_t)(now_ - start_);                                            \
            start_ = now_;                                                                     \
            *p->st->runtime = dt_;                                                             \
            int inc_ = dt_ > p->st->maxtime;                                                   \
            if (inc_)                                                                          \
                p->st->maxtime = dt_;                                                          \
            p->st->increased = inc_;                                                           \
        }                                                                                      \
        uint64_t t1_ = tsc();                                                                  \
        if (t1_ - t0_ < (best))                                                                \
            (best) = t1_ - t0_;                                                                \
    } while (0)

/* N reads alone; clocks. */
#define READS(READ, best)                                                                      \
    do {                                                                                       \
        uint64_t t0_ = tsc();                                                                  \
        for (int i_ = 0; i_ < N; i_++)                                                         \
            (void)READ();                                                                      \
        uint64_t t1_ = tsc();                                                                  \
        if (t1_ - t0_ < (best))                                                                \
            (best) = t1_ - t0_;                                                                \
    } while (0)

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
    uint64_t best_timed_p = UINT64_MAX, best_timed_f = UINT64_MAX;
    uint64_t best_tscp = UINT64_MAX, best_tscf = UINT64_MAX;
    for (int rep = 0; rep < 3000; rep++) {
        uint64_t t0 = tsc();
        for (entry_t *p = e; p < e + N; p++)
            p->f(p->arg, 100000);
        uint64_t t1 = tsc();
        if (t1 - t0 < best_loop)
            best_loop = t1 - t0;
        TIMED_PASS(tsc, e, best_timed);
        READS(tsc, best_tsc);
        TIMED_PASS(tscp, e, best_timed_p);
        TIMED_PASS(tscf, e, best_timed_f);
        READS(tscp, best_tscp);
        READS(tscf, best_tscf);
    }
    printf("%.2f %.2f %.2f %.2f %.2f %.2f %.2f\n", (double)best_loop / N, (double)best_timed / N,
           (double)best_tsc / N, (double)best_timed_p / N, (double)best_timed_f / N,
           (double)best_tscp / N, (double)best_tscf / N);
    return 0;
}
