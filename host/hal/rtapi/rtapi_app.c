/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_app - the realtime host of a HAL session.
 *
 * Started on demand by halcmd (one per HAL_INSTANCE), it listens on the
 * session's abstract unix socket, loads realtime components (NAME.so) with
 * their module parameters, owns the HAL threads, and exits once nothing is
 * loaded any more.  See docs/rtapi.md.
 *
 * Threads: on the wall clock each HAL thread is a pthread sleeping on an
 * absolute CLOCK_MONOTONIC deadline (SCHED_FIFO when permitted).  Under the
 * simulated clock one scheduler pthread runs all HAL threads in a single
 * deterministic order: virtual time jumps to the earliest due period.
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
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#include "hal_priv.h"

/* ---- captured messages ------------------------------------------------------ */

static pthread_mutex_t msg_lock = PTHREAD_MUTEX_INITIALIZER;
static char *msg_buf;
static size_t msg_len, msg_cap;
static int capturing;

/* Captured messages are sent as lines "E<text>" (for stderr: errors and
 * warnings) or "O<text>" (for stdout: info and debug, where LinuxCNC's
 * rtapi_app prints them), each ended by a NUL. */
static void msg_hook(int level, const char *text)
{
    pthread_mutex_lock(&msg_lock);
    if (capturing) {
        char tagged[1100];
        snprintf(tagged, sizeof(tagged), "%c%s", level <= RTAPI_MSG_WARN ? 'E' : 'O', text);
        text = tagged;
        size_t n = strlen(text) + 1; /* keep the NUL as separator */
        if (msg_len + n + 1 > msg_cap) {
            size_t cap = (msg_cap ? msg_cap * 2 : 1024) + n;
            char *nb = realloc(msg_buf, cap);
            if (nb != NULL) {
                msg_buf = nb;
                msg_cap = cap;
            }
        }
        if (msg_len + n + 1 <= msg_cap) {
            memcpy(msg_buf + msg_len, text, n);
            msg_len += n;
        }
    } else {
        FILE *f = level <= RTAPI_MSG_WARN ? stderr : stdout;
        fputs(text, f);
        fflush(f);
    }
    pthread_mutex_unlock(&msg_lock);
}

/* ---- threads ------------------------------------------------------------------ */

typedef struct {
    void (*funct)(void *, long);
    void *arg;
    hal_s32_t **runtime;
    hal_s32_t *maxtime;
    hal_bit_t *maxtime_increased;
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
        e[i].runtime = SHMPTR(f->runtime);
        e[i].maxtime = SHMPTR(f->maxtime);
        e[i].maxtime_increased = SHMPTR(f->maxtime_increased);
        i++;
    }
    hal_priv_unlock();
    free(rt->entries);
    rt->entries = e;
    rt->nentries = n;
    rt->gen = gen;
}

/* One period of one thread: the hot path.  The thread's own time is
 * measured every period; the functions' .time/.tmax every `timing_every`
 * periods (HAL_TIMING_EVERY, default 16; 1 = every period as LinuxCNC, 0 =
 * never), because reading the time-stamp counter around every function
 * costs more than calling a small function. */
static unsigned timing_every = 16;

static inline void run_cycle(rt_thread_t *rt, int measure)
{
    if (__builtin_expect(__atomic_load_n(&rt->t->gen, __ATOMIC_ACQUIRE) != rt->gen, 0))
        rebuild(rt);
    const long period = rt->t->period;
    rt_entry_t *e = rt->entries, *end = e + rt->nentries;
    if (!measure) {
        for (; e < end; e++)
            e->funct(e->arg, period);
        return;
    }
    long long t0 = rtapi_get_clocks(), start = t0;
    if (timing_every != 0 && ++rt->tick >= timing_every) {
        rt->tick = 0;
        for (; e < end; e++) {
            e->funct(e->arg, period);
            long long now = rtapi_get_clocks();
            hal_s32_t dt = (hal_s32_t)(now - start);
            **e->runtime = dt;
            if (dt > *e->maxtime) {
                *e->maxtime = dt;
                *e->maxtime_increased = 1;
            } else {
                *e->maxtime_increased = 0;
            }
            start = now;
        }
    } else {
        for (; e < end; e++)
            e->funct(e->arg, period);
        start = rtapi_get_clocks();
    }
    hal_s32_t total = (hal_s32_t)(start - t0);
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

static const hal_thread_hooks_t thread_hooks = {hook_thread_created, hook_thread_deleting};

/* Wait until no thread is in the middle of a period that started before
 * now (so functions removed from the lists are no longer running). */
static void quiesce(void)
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

static volatile sig_atomic_t got_signal;
static void on_signal(int sig)
{
    (void)sig;
    got_signal = 1;
}

/* ---- modules ------------------------------------------------------------------- */

typedef struct module {
    struct module *next;
    char name[HAL_NAME_LEN + 1];
    void *handle;
    int ncomps;
    int comp_ids[64];
    char **strings; /* string parameter values given to the module */
    int nstrings;
} module_t;

static void free_strings(module_t *m)
{
    for (int i = 0; i < m->nstrings; i++)
        free(m->strings[i]);
    free(m->strings);
    m->strings = NULL;
    m->nstrings = 0;
}

static module_t *modules;

static int find_module_file(const char *name, char *path, size_t len)
{
    if (strchr(name, '/') != NULL || strlen(name) > HAL_NAME_LEN)
        return -EINVAL;
    const char *env = getenv("HAL_RTLIB_DIR");
    if (env != NULL && *env) {
        char *dirs = strdup(env), *save = NULL;
        if (dirs == NULL)
            return -ENOMEM;
        for (char *d = strtok_r(dirs, ":", &save); d; d = strtok_r(NULL, ":", &save)) {
            if ((size_t)snprintf(path, len, "%s/%s.so", d, name) < len &&
                access(path, R_OK) == 0) {
                free(dirs);
                return 0;
            }
        }
        free(dirs);
    }
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
    if (n > 0) {
        self[n] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) {
            *slash = '\0';
            if ((size_t)snprintf(path, len, "%s/../lib/rtlib/%s.so", self, name) < len &&
                access(path, R_OK) == 0)
                return 0;
            if ((size_t)snprintf(path, len, "%s/rtlib/%s.so", self, name) < len &&
                access(path, R_OK) == 0)
                return 0;
        }
    }
    return -ENOENT;
}

static int parse_long(const char *s, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 0);
    if (*s == '\0' || *end != '\0' || errno == ERANGE)
        return -EINVAL;
    *out = v;
    return 0;
}

/* Set one module parameter key=value; messages as LinuxCNC's rtapi_app. */
static int set_param(void *handle, const char *arg, module_t *m)
{
    const char *eq = strchr(arg, '=');
    char key[128];
    if (eq == NULL || eq == arg || (size_t)(eq - arg) >= sizeof(key)) {
        rtapi_print_msg(RTAPI_MSG_ERR, "Unknown parameter `%s'\n", arg);
        return -EINVAL;
    }
    memcpy(key, arg, (size_t)(eq - arg));
    key[eq - arg] = '\0';
    const char *value = eq + 1;
    char sym[192];
    snprintf(sym, sizeof(sym), "rtapi_info_address_%s", key);
    void **addrp = dlsym(handle, sym);
    snprintf(sym, sizeof(sym), "rtapi_info_type_%s", key);
    const char **typep = dlsym(handle, sym);
    if (addrp == NULL || typep == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "Unknown parameter `%s'\n", arg);
        return -EINVAL;
    }
    snprintf(sym, sizeof(sym), "rtapi_info_size_%s", key);
    int *sizep = dlsym(handle, sym);
    int count = sizep ? *sizep : 1;
    int is_array = sizep != NULL;
    char type = (*typep)[0];
    /* Parse everything first so a bad element changes nothing. */
    char *copy = strdup(value);
    if (copy == NULL)
        return -ENOMEM;
    /* halcmd passes config="a b,c d" with its quotes; LinuxCNC's halcmd
     * drops them before the module sees the value, so arrays split into
     * "a b" and "c d", not "\"a b" and "c d\"". */
    size_t vlen = strlen(copy);
    if (vlen >= 2 && copy[0] == '"' && copy[vlen - 1] == '"') {
        memmove(copy, copy + 1, vlen - 2);
        copy[vlen - 2] = '\0';
    }
    char *items[1024];
    int nitems = 0;
    if (is_array) {
        char *p = copy;
        for (;;) {
            if (nitems >= count || nitems >= 1024) {
                rtapi_print_msg(RTAPI_MSG_ERR,
                                "Too many values for parameter `%s' (at most %d)\n", arg,
                                count);
                free(copy);
                return -EINVAL;
            }
            items[nitems++] = p;
            char *comma = strchr(p, ',');
            if (comma == NULL)
                break;
            *comma = '\0';
            p = comma + 1;
        }
    } else {
        items[nitems++] = copy;
    }
    long lv[1024];
    for (int i = 0; i < nitems; i++) {
        if (type == 'i' || type == 'l') {
            if (parse_long(items[i], &lv[i]) != 0 ||
                (type == 'i' && (lv[i] < INT_MIN || lv[i] > INT_MAX))) {
                rtapi_print_msg(RTAPI_MSG_ERR, "`%s' invalid for parameter `%s'\n", items[i],
                                arg);
                free(copy);
                return -EINVAL;
            }
        } else if (type != 's') {
            rtapi_print_msg(RTAPI_MSG_ERR, "parameter `%s' has unknown type `%s'\n", key,
                            *typep);
            free(copy);
            return -EINVAL;
        }
    }
    void *addr = *addrp;
    for (int i = 0; i < nitems; i++) {
        if (type == 'i')
            ((int *)addr)[i] = (int)lv[i];
        else if (type == 'l')
            ((long *)addr)[i] = lv[i];
        else {
            /* The string lives as long as the module is loaded. */
            char *s = strdup(items[i]);
            char **v = realloc(m->strings, sizeof(char *) * (size_t)(m->nstrings + 1));
            if (s == NULL || v == NULL) {
                free(s);
                if (v != NULL)
                    m->strings = v;
                free(copy);
                return -ENOMEM;
            }
            m->strings = v;
            m->strings[m->nstrings++] = s;
            ((char **)addr)[i] = s;
        }
    }
    free(copy);
    return 0;
}

static int comp_ids_snapshot(int *ids, int max)
{
    int n = 0;
    hal_priv_lock();
    for (hal_off_t off = hal_hdr->comp_list; off; off = ((hal_comp_t *)SHMPTR(off))->next)
        if (n < max)
            ids[n++] = ((hal_comp_t *)SHMPTR(off))->id;
    hal_priv_unlock();
    return n;
}

static int do_load(int argc, char **argv)
{
    if (argc < 2)
        return -EINVAL;
    const char *name = argv[1];
    for (module_t *m = modules; m; m = m->next)
        if (strcmp(m->name, name) == 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: already exists\n", name);
            return -EEXIST;
        }
    char path[PATH_MAX];
    if (find_module_file(name, path, sizeof(path)) != 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: dlopen: %s.so: cannot open shared object file: "
                        "No such file or directory\n", name, name);
        return -ENOENT;
    }
    void *h = dlopen(path, RTLD_NOW | RTLD_GLOBAL);
    if (h == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: dlopen: %s\n", name, dlerror());
        return -ENOENT;
    }
    int (*app_main)(void) = (int (*)(void))dlsym(h, "rtapi_app_main");
    if (app_main == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: dlsym: %s\n", name, dlerror());
        dlclose(h);
        return -ENOENT;
    }
    module_t *m = calloc(1, sizeof(*m));
    if (m == NULL) {
        dlclose(h);
        return -ENOMEM;
    }
    for (int i = 2; i < argc; i++) {
        if (set_param(h, argv[i], m) != 0) {
            dlclose(h);
            free_strings(m);
            free(m);
            return -EINVAL;
        }
    }
    int before[1024];
    int nbefore = comp_ids_snapshot(before, 1024);
    int rc = app_main();
    if (rc < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: rtapi_app_main: %s (%d)\n", name, strerror(-rc), rc);
        /* Components the failed module left behind go with it. */
        int after[1024];
        int nafter = comp_ids_snapshot(after, 1024);
        for (int i = 0; i < nafter; i++) {
            int found = 0;
            for (int j = 0; j < nbefore; j++)
                if (before[j] == after[i])
                    found = 1;
            if (!found)
                halpr_comp_delete(after[i]);
        }
        __atomic_add_fetch(&hal_hdr->sim_abort, 1, __ATOMIC_RELEASE);
        quiesce();
        dlclose(h);
        free_strings(m);
        free(m);
        return rc;
    }
    int after[1024];
    int nafter = comp_ids_snapshot(after, 1024);
    for (int i = 0; i < nafter && m->ncomps < 64; i++) {
        int found = 0;
        for (int j = 0; j < nbefore; j++)
            if (before[j] == after[i])
                found = 1;
        if (!found)
            m->comp_ids[m->ncomps++] = after[i];
    }
    snprintf(m->name, sizeof(m->name), "%s", name);
    m->handle = h;
    m->next = modules;
    modules = m;
    /* The loadrt arguments, for `save`. */
    char args[HAL_ARGS_LEN];
    args[0] = '\0';
    size_t used = 0;
    for (int i = 2; i < argc; i++) {
        int n = snprintf(args + used, sizeof(args) - used, "%s ", argv[i]);
        if (n < 0 || (size_t)n >= sizeof(args) - used)
            break;
        used += (size_t)n;
    }
    halpr_set_insmod_args(name, args);
    return 0;
}

static void remove_functs_of(module_t *m)
{
    hal_priv_lock();
    for (hal_off_t toff = hal_hdr->thread_list; toff;) {
        hal_thread_t *t = SHMPTR(toff);
        for (hal_off_t off = t->funct_list; off;) {
            hal_funct_entry_t *e = SHMPTR(off);
            off = e->next;
            hal_funct_t *f = SHMPTR(e->funct);
            hal_comp_t *c = SHMPTR(f->owner);
            for (int i = 0; i < m->ncomps; i++)
                if (c->id == m->comp_ids[i]) {
                    char fn[HAL_NAME_LEN + 1], tn[HAL_NAME_LEN + 1];
                    snprintf(fn, sizeof(fn), "%s", f->name);
                    snprintf(tn, sizeof(tn), "%s", t->name);
                    hal_priv_unlock();
                    hal_del_funct_from_thread(fn, tn);
                    hal_priv_lock();
                    off = t->funct_list; /* list changed: rescan */
                    break;
                }
        }
        toff = t->next;
    }
    hal_priv_unlock();
}

static int unload_module(module_t *m)
{
    /* Functions leave the threads before the module's exit code runs,
     * and the code stays mapped until no period is still inside it. */
    remove_functs_of(m);
    /* A function waiting in rtapi_sim_yield() for a peer gives up now. */
    __atomic_add_fetch(&hal_hdr->sim_abort, 1, __ATOMIC_RELEASE);
    quiesce();
    void (*app_exit)(void) = (void (*)(void))dlsym(m->handle, "rtapi_app_exit");
    if (app_exit != NULL)
        app_exit();
    for (int i = 0; i < m->ncomps; i++)
        halpr_comp_delete(m->comp_ids[i]); /* what the module forgot */
    quiesce();
    dlclose(m->handle);
    module_t **pp = &modules;
    while (*pp != m)
        pp = &(*pp)->next;
    *pp = m->next;
    free_strings(m);
    free(m);
    return 0;
}

static int do_unload(int argc, char **argv)
{
    if (argc < 2)
        return -EINVAL;
    for (module_t *m = modules; m; m = m->next)
        if (strcmp(m->name, argv[1]) == 0)
            return unload_module(m);
    rtapi_print_msg(RTAPI_MSG_ERR, "%s: not loaded\n", argv[1]);
    return -ENOENT;
}

static int do_simrun(int argc, char **argv)
{
    long v;
    if (argc < 2 || parse_long(argv[1], &v) != 0 || v < 0) {
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
        if (got_signal && simrun_active) {
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

/* ---- server --------------------------------------------------------------------- */

static int read_full(int fd, void *buf, size_t len)
{
    char *p = buf;
    while (len) {
        ssize_t n = read(fd, p, len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return -1;
        p += n;
        len -= (size_t)n;
    }
    return 0;
}

static void write_full(int fd, const void *buf, size_t len)
{
    const char *p = buf;
    while (len) {
        ssize_t n = write(fd, p, len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return;
        p += n;
        len -= (size_t)n;
    }
}

static int quit_requested;

static void unload_all(void)
{
    while (modules != NULL)
        unload_module(modules);
}

static int handle(int argc, char **argv, char **listing)
{
    *listing = NULL;
    if (argc == 0)
        return -EINVAL;
    if (strcmp(argv[0], "load") == 0)
        return do_load(argc, argv);
    if (strcmp(argv[0], "unload") == 0)
        return do_unload(argc, argv);
    if (strcmp(argv[0], "simrun") == 0)
        return do_simrun(argc, argv);
    if (strcmp(argv[0], "ping") == 0)
        return 0;
    if (strcmp(argv[0], "list") == 0) {
        size_t cap = 16;
        for (module_t *m = modules; m; m = m->next)
            cap += strlen(m->name) + 1;
        char *s = calloc(1, cap);
        if (s == NULL)
            return -ENOMEM;
        for (module_t *m = modules; m; m = m->next) {
            strcat(s, m->name);
            strcat(s, "\n");
        }
        *listing = s;
        return 0;
    }
    if (strcmp(argv[0], "exit") == 0) {
        unload_all();
        quit_requested = 1;
        return 0;
    }
    rtapi_print_msg(RTAPI_MSG_ERR, "rtapi_app: unknown request '%s'\n", argv[0]);
    return -EINVAL;
}

static void serve_one(int cfd)
{
    uint32_t len;
    if (read_full(cfd, &len, 4) != 0 || len > (1u << 20))
        return;
    char *buf = malloc(len + 1);
    if (buf == NULL)
        return;
    if (read_full(cfd, buf, len) != 0) {
        free(buf);
        return;
    }
    buf[len] = '\0';
    char *argv[512];
    int argc = 0;
    for (char *p = buf; p < buf + len && argc < 511; p += strlen(p) + 1)
        argv[argc++] = p;
    argv[argc] = NULL;
    pthread_mutex_lock(&msg_lock);
    capturing = 1;
    msg_len = 0;
    if (msg_buf)
        msg_buf[0] = '\0';
    pthread_mutex_unlock(&msg_lock);
    char *listing = NULL;
    int32_t st = handle(argc, argv, &listing);
    pthread_mutex_lock(&msg_lock);
    capturing = 0;
    const char *out = listing ? listing : (msg_buf ? msg_buf : "");
    uint32_t olen = listing ? (uint32_t)strlen(listing) : (uint32_t)msg_len;
    write_full(cfd, &st, 4);
    write_full(cfd, &olen, 4);
    write_full(cfd, out, olen);
    msg_len = 0;
    pthread_mutex_unlock(&msg_lock);
    free(listing);
    free(buf);
}


int main(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    signal(SIGPIPE, SIG_IGN);
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);

    int lfd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (lfd < 0) {
        perror("rtapi_app: socket");
        return 1;
    }
    struct sockaddr_un addr;
    memset(&addr, 0, sizeof(addr));
    addr.sun_family = AF_UNIX;
    char name[sizeof(addr.sun_path)];
    hal_priv_socket_name(name, sizeof(name));
    size_t n = 1 + strlen(name + 1);
    memcpy(addr.sun_path, name, n);
    if (bind(lfd, (struct sockaddr *)&addr,
             (socklen_t)(offsetof(struct sockaddr_un, sun_path) + n)) != 0) {
        /* Another rtapi_app of this session got there first. */
        close(lfd);
        return errno == EADDRINUSE ? 0 : 1;
    }
    if (listen(lfd, 16) != 0) {
        perror("rtapi_app: listen");
        return 1;
    }
    hal_priv_set_realtime_host(1);
    rtapi_priv_set_msg_hook(msg_hook);
    if (hal_priv_attach() != 0)
        return 1;
    hal_priv_set_thread_hooks(&thread_hooks);
    hal_hdr->rtapi_pid = getpid();
    simclock = hal_hdr->simclock;
    const char *te = getenv("HAL_TIMING_EVERY");
    if (te != NULL && *te) {
        char *end;
        unsigned long v = strtoul(te, &end, 10);
        if (*end == '\0' && v <= 1000000)
            timing_every = (unsigned)v;
    }
    if (simclock) {
        if (pthread_create(&sim_tid, NULL, sim_main, NULL) != 0) {
            fprintf(stderr, "rtapi_app: cannot start the simulated-clock scheduler\n");
            return 1;
        }
        sim_started = 1;
    }
    /* Serve until nothing is loaded any more (checked after each request,
     * so the request that started us is served first). */
    int served = 0;
    while (!quit_requested && !got_signal) {
        struct timeval tv = {0, 200000};
        fd_set rfds;
        FD_ZERO(&rfds);
        FD_SET(lfd, &rfds);
        int r = select(lfd + 1, &rfds, NULL, NULL, &tv);
        if (r > 0) {
            int cfd = accept4(lfd, NULL, NULL, SOCK_CLOEXEC);
            if (cfd >= 0) {
                serve_one(cfd);
                close(cfd);
                served++;
            }
        } else if (served == 0) {
            /* Started but nobody asked anything for 10 s: give up. */
            static int idle;
            if (++idle > 50)
                break;
        }
        if (served > 0 && modules == NULL && rt_threads == NULL)
            break;
        /* The session was destroyed under us (halrun -U): leave. */
        if (hal_priv_session_state() == 0)
            break;
    }
    /* Stop taking requests before tearing down. */
    close(lfd);
    unload_all();
    if (sim_started) {
        sim_exit = 1;
        pthread_join(sim_tid, NULL);
    }
    if (hal_hdr->rtapi_pid == getpid())
        hal_hdr->rtapi_pid = 0;
    free(msg_buf);
    return 0;
}
