/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_threads.c - rtapi_app's HAL threads.  On the wall clock each HAL
 * thread is a pthread sleeping on an absolute CLOCK_MONOTONIC deadline
 * (SCHED_FIFO when permitted).  Under the simulated clock one scheduler
 * pthread runs all HAL threads in a single deterministic order: virtual
 * time jumps to the earliest due period.
 *
 * The dispatch loop takes no lock and looks up nothing by name: it works
 * on a private array of {function, argument, timing storage} that it
 * rebuilds (under the HAL mutex) only when the thread's generation counter
 * in shared memory says the function list changed.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "rtapi_app.h"

/* One function of a thread, as the dispatch loop needs it: a contiguous
 * array of these, no offsets to translate. */
typedef struct {
    void (*funct)(void *, long);
    void *arg;
    hal_funct_store_t *st; /* .time pin pointer, .tmax, .tmax-increased */
} rt_entry_t;

typedef struct rt_thread {
    struct rt_thread *next;
    hal_thread_t *t;
    pthread_t tid;
    volatile int stop;
    int busy; /* sim scheduler is running it (guarded by rt_lock) */
    volatile int in_cycle;          /* wall clock: inside a period */
    volatile unsigned long cycles;  /* wall clock: periods begun */
    uint32_t gen;
    int nentries;
    rt_entry_t *entries;
    long long next_due; /* simulated clock */
    unsigned tick;      /* periods since functions were last timed */
    int order;
} rt_thread_t;

static pthread_mutex_t rt_lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t rt_cond = PTHREAD_COND_INITIALIZER;
static rt_thread_t *rt_threads;
static int rt_order;
static int simclock;
static pthread_t sim_tid;
static int sim_started;
static volatile int sim_exit;
/* simrun: guarded by rt_lock */
static int simrun_active;
static long long simrun_target;
static int simrun_prev_running;
static pthread_cond_t simrun_cond = PTHREAD_COND_INITIALIZER;

static void rebuild(rt_thread_t *rt)
{
    hal_priv_lock();
    hal_thread_t *t = rt->t;
    uint32_t gen = __atomic_load_n(&t->gen, __ATOMIC_ACQUIRE);
    int n = 0;
    for (hal_off_t off = t->funct_list; off; off = ((hal_funct_entry_t *)SHMPTR(off))->next)
        n++;
    rt_entry_t *e = n ? calloc((size_t)n, sizeof(*e)) : NULL;
    if (n && e == NULL) {
        hal_priv_unlock();
        return; /* keep the old list; retried next period */
    }
    int i = 0;
    for (hal_off_t off = t->funct_list; off; off = ((hal_funct_entry_t *)SHMPTR(off))->next) {
        hal_funct_t *f = SHMPTR(((hal_funct_entry_t *)SHMPTR(off))->funct);
        e[i].funct = (void (*)(void *, long))(uintptr_t)f->funct;
        e[i].arg = (void *)(uintptr_t)f->arg;
        e[i].st = SHMPTR(f->runtime); /* the store starts with the .time pointer */
        i++;
    }
    hal_priv_unlock();
    free(rt->entries);
    rt->entries = e;
    rt->nentries = n;
    rt->gen = gen;
}

/* The time-stamp counter, inline: the dispatch loop reads it after every
 * function, so a call into libhal (rtapi_get_clocks) would cost more than
 * a small function. */
static inline uint64_t clocks(void)
{
#if defined(__x86_64__) || defined(__i386__)
    unsigned int lo, hi;
    __asm__ __volatile__("rdtsc" : "=a"(lo), "=d"(hi));
    return ((uint64_t)hi << 32) | lo;
#else
    return (uint64_t)rtapi_get_clocks();
#endif
}

/* Entries ahead of the running one whose timing storage is prefetched:
 * with tens of thousands of functions (100k pins) the table, the stores and
 * the .time pins no longer fit the caches, and the misses cost more than
 * the time-stamp read (bench/hal, best period: 49-53 -> 34-47 clocks per
 * function at 100k pins; no change at 1k). */
#define RT_PREFETCH 4

/* Run the functions, timing each (LinuxCNC's .time, .tmax,
 * .tmax-increased): one time-stamp read per function, the end of one is
 * the start of the next; returns the clock after the last one.  rdtsc, not
 * rdtscp or lfence;rdtsc: those order the read after the function's last
 * instruction (a few clocks of attribution) but cost ~2x per function
 * (bench/hal/floor.c), and the sum over a thread is the same. */
static inline uint64_t run_timed(const rt_entry_t *e, const rt_entry_t *end, long period,
                                 uint64_t start)
{
    for (; e < end; e++) {
        if (e + 2 * RT_PREFETCH < end) {
            __builtin_prefetch(e[2 * RT_PREFETCH].st, 1);
            __builtin_prefetch(e[2 * RT_PREFETCH].arg);
            __builtin_prefetch((const void *)(uintptr_t)e[RT_PREFETCH].st->runtime, 1);
        }
        e->funct(e->arg, period);
        uint64_t now = clocks();
        hal_s32_t dt = (hal_s32_t)(now - start);
        start = now;
        hal_funct_store_t *st = e->st;
        *st->runtime = dt;
        int inc = dt > st->maxtime;
        if (inc)
            st->maxtime = dt;
        st->maxtime_increased = inc;
    }
    return start;
}

/* One period of one thread: the hot path.  The thread's own time and, by
 * default, every function's .time/.tmax are measured every period, as in
 * LinuxCNC, so .tmax is the worst case over all periods.
 * HAL_TIMING_EVERY=N times the functions only every Nth period (0 =
 * never), for those who want the last clocks of dispatch speed instead. */
static unsigned timing_every = 1;

static inline void run_cycle(rt_thread_t *rt, int measure)
{
    if (__builtin_expect(__atomic_load_n(&rt->t->gen, __ATOMIC_ACQUIRE) != rt->gen, 0))
        rebuild(rt);
    const long period = rt->t->period;
    const rt_entry_t *e = rt->entries, *end = e + rt->nentries;
    if (!measure) {
        for (; e < end; e++)
            e->funct(e->arg, period);
        return;
    }
    uint64_t t0 = clocks(), t1;
    if (timing_every == 1 || (timing_every != 0 && ++rt->tick >= timing_every)) {
        rt->tick = 0;
        t1 = run_timed(e, end, period, t0);
    } else {
        for (; e < end; e++)
            e->funct(e->arg, period);
        t1 = clocks();
    }
    hal_s32_t total = (hal_s32_t)(t1 - t0);
    hal_s32_t **rtp = SHMPTR(rt->t->runtime);
    **rtp = total;
    hal_s32_t *mx = SHMPTR(rt->t->maxtime);
    if (total > *mx)
        *mx = total;
}

static void *wall_thread_main(void *arg)
{
    rt_thread_t *rt = arg;
    rtapi_priv_set_in_realtime(1);
    struct timespec next;
    clock_gettime(CLOCK_MONOTONIC, &next);
    const long period = rt->t->period;
    while (!rt->stop) {
        next.tv_nsec += period;
        while (next.tv_nsec >= 1000000000L) {
            next.tv_nsec -= 1000000000L;
            next.tv_sec++;
        }
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL) == EINTR)
            ;
        if (rt->stop)
            break;
        if (hal_hdr->threads_running) {
            /* in_cycle is set before the generation check in run_cycle,
             * so quiesce() can tell whether this period may still use a
             * function list from before a change. */
            __atomic_store_n(&rt->in_cycle, 1, __ATOMIC_SEQ_CST);
            run_cycle(rt, 1);
            __atomic_add_fetch(&rt->cycles, 1, __ATOMIC_SEQ_CST);
            __atomic_store_n(&rt->in_cycle, 0, __ATOMIC_SEQ_CST);
        }
        /* Overrun by more than a period: resynchronise instead of
         * running a burst of late periods. */
        struct timespec now;
        clock_gettime(CLOCK_MONOTONIC, &now);
        long long late = (now.tv_sec - next.tv_sec) * 1000000000LL + (now.tv_nsec - next.tv_nsec);
        if (late > period)
            next = now;
    }
    return NULL;
}

static rt_thread_t *sim_pick(void)
{
    rt_thread_t *best = NULL;
    for (rt_thread_t *r = rt_threads; r; r = r->next) {
        if (best == NULL || r->next_due < best->next_due ||
            (r->next_due == best->next_due &&
             (r->t->period < best->t->period ||
              (r->t->period == best->t->period && r->order < best->order))))
            best = r;
    }
    return best;
}

static void *sim_main(void *arg)
{
    (void)arg;
    rtapi_priv_set_in_realtime(1);
    int was_running = 0;
    while (!sim_exit) {
        pthread_mutex_lock(&rt_lock);
        int running = hal_hdr->threads_running;
        long long now = hal_hdr->sim_time;
        if (running && !was_running) {
            /* Threads keep their phase across stop/start, as a periodic
             * timer would; only periods already in the past are skipped. */
            for (rt_thread_t *r = rt_threads; r; r = r->next)
                while (r->next_due <= now)
                    r->next_due += r->t->period;
        }
        was_running = running;
        rt_thread_t *r = running ? sim_pick() : NULL;
        if (simrun_active && (r == NULL || r->next_due > simrun_target)) {
            /* The run is over: virtual time stands exactly at the target. */
            if (now < simrun_target)
                __atomic_store_n(&hal_hdr->sim_time, simrun_target, __ATOMIC_RELEASE);
            hal_hdr->threads_running = simrun_prev_running;
            was_running = simrun_prev_running;
            simrun_active = 0;
            pthread_cond_broadcast(&simrun_cond);
            pthread_mutex_unlock(&rt_lock);
            continue;
        }
        if (r == NULL) {
            pthread_mutex_unlock(&rt_lock);
            struct timespec ts = {0, 200000};
            nanosleep(&ts, NULL);
            continue;
        }
        r->busy = 1;
        __atomic_store_n(&hal_hdr->sim_time, r->next_due, __ATOMIC_RELEASE);
        r->next_due += r->t->period;
        pthread_mutex_unlock(&rt_lock);
        rtapi_priv_sim_cycle_begin();
        run_cycle(r, 0);
        pthread_mutex_lock(&rt_lock);
        r->busy = 0;
        pthread_cond_broadcast(&rt_cond);
        pthread_mutex_unlock(&rt_lock);
    }
    return NULL;
}

static int hook_thread_created(hal_thread_t *t)
{
    rt_thread_t *rt = calloc(1, sizeof(*rt));
    if (rt == NULL)
        return -ENOMEM;
    rt->t = t;
    rt->gen = (uint32_t)-1;
    rt->tick = timing_every ? timing_every - 1 : 0; /* time the first period */
    rt->order = rt_order++;
    if (simclock) {
        pthread_mutex_lock(&rt_lock);
        rt->next_due = hal_hdr->sim_time + t->period;
        rt->next = rt_threads;
        rt_threads = rt;
        pthread_mutex_unlock(&rt_lock);
        return 0;
    }
    pthread_attr_t attr;
    pthread_attr_init(&attr);
    struct sched_param sp;
    /* Faster threads get higher priority, as in LinuxCNC. */
    int prio = sched_get_priority_max(SCHED_FIFO) - 1 - t->priority;
    if (prio < sched_get_priority_min(SCHED_FIFO))
        prio = sched_get_priority_min(SCHED_FIFO);
    sp.sched_priority = prio;
    pthread_attr_setinheritsched(&attr, PTHREAD_EXPLICIT_SCHED);
    pthread_attr_setschedpolicy(&attr, SCHED_FIFO);
    pthread_attr_setschedparam(&attr, &sp);
    int rc = pthread_create(&rt->tid, &attr, wall_thread_main, rt);
    pthread_attr_destroy(&attr);
    if (rc == EPERM || rc == EINVAL) {
        /* Not permitted to run SCHED_FIFO: plain scheduling. */
        rc = pthread_create(&rt->tid, NULL, wall_thread_main, rt);
    }
    if (rc != 0) {
        free(rt);
        return -rc;
    }
    pthread_mutex_lock(&rt_lock);
    rt->next = rt_threads;
    rt_threads = rt;
    pthread_mutex_unlock(&rt_lock);
    return 0;
}

static void hook_thread_deleting(hal_thread_t *t)
{
    pthread_mutex_lock(&rt_lock);
    rt_thread_t **pp = &rt_threads, *rt = NULL;
    for (; *pp; pp = &(*pp)->next)
        if ((*pp)->t == t) {
            rt = *pp;
            break;
        }
    if (rt == NULL) {
        pthread_mutex_unlock(&rt_lock);
        return;
    }
    while (rt->busy)
        pthread_cond_wait(&rt_cond, &rt_lock);
    *pp = rt->next;
    pthread_mutex_unlock(&rt_lock);
    if (!simclock) {
        rt->stop = 1;
        pthread_join(rt->tid, NULL);
    }
    free(rt->entries);
    free(rt);
}

const hal_thread_hooks_t rtapi_thread_hooks = {hook_thread_created, hook_thread_deleting};

/* Wait until no thread is in the middle of a period that started before
 * now (so functions removed from the lists are no longer running). */
void rtapi_quiesce(void)
{
    if (simclock) {
        pthread_mutex_lock(&rt_lock);
        for (rt_thread_t *r = rt_threads; r; r = r->next)
            while (r->busy)
                pthread_cond_wait(&rt_cond, &rt_lock);
        pthread_mutex_unlock(&rt_lock);
        return;
    }
    /* Wall clock: the function lists were changed (generation bumped)
     * before we got here; a thread not inside a period will rebuild before
     * calling anything, one inside a period is waited for. */
    pthread_mutex_lock(&rt_lock);
    for (rt_thread_t *r = rt_threads; r; r = r->next) {
        unsigned long c = __atomic_load_n(&r->cycles, __ATOMIC_SEQ_CST);
        while (__atomic_load_n(&r->in_cycle, __ATOMIC_SEQ_CST) &&
               __atomic_load_n(&r->cycles, __ATOMIC_SEQ_CST) == c) {
            struct timespec ts = {0, 20000};
            nanosleep(&ts, NULL);
        }
    }
    pthread_mutex_unlock(&rt_lock);
}

int rtapi_do_simrun(int argc, char **argv)
{
    long v;
    if (argc < 2 || rtapi_parse_long(argv[1], &v) != 0 || v < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "simrun: bad duration '%s'\n", argc > 1 ? argv[1] : "");
        return -EINVAL;
    }
    if (!simclock) {
        rtapi_print_msg(RTAPI_MSG_ERR, "simrun: the session does not run on the simulated clock\n");
        return -EPERM;
    }
    pthread_mutex_lock(&rt_lock);
    simrun_target = hal_hdr->sim_time + v;
    simrun_prev_running = hal_hdr->threads_running;
    simrun_active = 1;
    hal_hdr->threads_running = 1;
    int rc = 0;
    while (simrun_active) {
        struct timespec dl;
        clock_gettime(CLOCK_REALTIME, &dl);
        dl.tv_nsec += 100000000L;
        if (dl.tv_nsec >= 1000000000L) {
            dl.tv_nsec -= 1000000000L;
            dl.tv_sec++;
        }
        pthread_cond_timedwait(&simrun_cond, &rt_lock, &dl);
        if (rtapi_got_signal && simrun_active) {
            /* Terminated while running: stop the threads and give up. */
            hal_hdr->threads_running = 0;
            __atomic_add_fetch(&hal_hdr->sim_abort, 1, __ATOMIC_RELEASE);
            rc = -EINTR;
            while (simrun_active)
                pthread_cond_wait(&simrun_cond, &rt_lock);
        }
    }
    pthread_mutex_unlock(&rt_lock);
    return rc;
}

int rtapi_threads_init(int sim)
{
    simclock = sim;
    const char *te = getenv("HAL_TIMING_EVERY");
    if (te != NULL && *te) {
        char *end;
        unsigned long v = strtoul(te, &end, 10);
        if (*end == '\0' && v <= 1000000)
            timing_every = (unsigned)v;
    }
    if (simclock) {
        int rc = pthread_create(&sim_tid, NULL, sim_main, NULL);
        if (rc != 0)
            return -rc;
        sim_started = 1;
    }
    return 0;
}

void rtapi_threads_exit(void)
{
    if (sim_started) {
        sim_exit = 1;
        pthread_join(sim_tid, NULL);
        sim_started = 0;
    }
}

int rtapi_threads_exist(void) { return rt_threads != NULL; }
