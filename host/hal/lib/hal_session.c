/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_session.c - the life of a HAL session outside its segment's
 * contents: which processes belong to it and whether they live, the
 * private runtime directory (rtapi_app's log), cleaning up after a crash
 * (halrun -U) and removing a session nobody uses any more.
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hal_priv.h"

/* ---- processes ------------------------------------------------------------------ */

/* Field 22 of /proc/PID/stat (start time in clock ticks), 0 when the
 * process does not exist or is a zombie. */
static unsigned long long proc_start_time(int pid)
{
    char path[64], buf[512];
    snprintf(path, sizeof(path), "/proc/%d/stat", pid);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return 0;
    size_t n = fread(buf, 1, sizeof(buf) - 1, f);
    fclose(f);
    buf[n] = '\0';
    const char *p = strrchr(buf, ')');
    if (p == NULL || p[1] != ' ' || p[2] == 'Z' || p[2] == 'X')
        return 0;
    /* after ") " come fields 3 (state) ... 22 (starttime) */
    p += 2;
    for (int field = 3; field < 22; field++) {
        p = strchr(p, ' ');
        if (p == NULL)
            return 0;
        p++;
    }
    return strtoull(p, NULL, 10);
}

unsigned long long hal_priv_self_start_time(void) { return proc_start_time(getpid()); }

/* Alive and not a zombie (a killed rtapi_app may stay a zombie for a
 * while when its reaper is slow). */
int hal_priv_pid_alive(int pid)
{
    if (pid <= 0)
        return 0;
    if (kill(pid, 0) != 0 && errno != EPERM)
        return 0;
    return proc_start_time(pid) != 0;
}

/* The session's rtapi_app is alive: same pid and same start time (a pid
 * reused by another program does not count). */
static int rtapi_alive(const hal_hdr_t *h)
{
    if (h->rtapi_pid <= 0)
        return 0;
    unsigned long long st = proc_start_time(h->rtapi_pid);
    return st != 0 && (h->rtapi_start == 0 || st == h->rtapi_start);
}

/* ---- looking at a segment without joining it ------------------------------------ */

typedef struct {
    const hal_hdr_t *h;
    size_t size;
} peek_t;

static int peek_open(peek_t *pk)
{
    int fd = shm_open(hal_priv_shm_name(), O_RDONLY | O_NOFOLLOW, 0600);
    if (fd < 0)
        return -errno;
    struct stat st;
    if (fstat(fd, &st) != 0 || (size_t)st.st_size < sizeof(hal_hdr_t)) {
        close(fd);
        return -EINVAL;
    }
    void *p = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_SHARED, fd, 0);
    close(fd);
    if (p == MAP_FAILED)
        return -EINVAL;
    pk->h = p;
    pk->size = (size_t)st.st_size;
    const hal_hdr_t *h = p;
    if (h->magic != HAL_SHM_MAGIC || h->version != HAL_SHM_VERSION || h->size != pk->size) {
        munmap(p, pk->size);
        return -EINVAL;
    }
    return 0;
}

static void peek_close(peek_t *pk) { munmap((void *)pk->h, pk->size); }

/* What lives in the session.  Read without the lock (it may be held by a
 * dead process); the lists are only walked, with a guard. */
typedef struct {
    int rtapi_alive;
    int rt_comps;    /* realtime components (threads included) */
    int user_alive;  /* user components whose process lives */
    int user_dead;   /* user components whose process is gone */
    int other_comps; /* components of this very process */
    int sigs;
} census_t;

static void census(const hal_hdr_t *h, census_t *c)
{
    memset(c, 0, sizeof(*c));
    c->rtapi_alive = rtapi_alive(h);
    hal_off_t off = h->comp_list;
    for (int guard = 0; off != 0 && off < h->size && guard < 100000; guard++) {
        const hal_comp_t *comp = (const hal_comp_t *)((const char *)h + off);
        if (comp->type == HAL_COMP_RT)
            c->rt_comps++;
        else if (comp->pid == getpid())
            c->other_comps++;
        else if (hal_priv_pid_alive(comp->pid))
            c->user_alive++;
        else
            c->user_dead++;
        off = comp->next;
    }
    c->sigs = h->sig_list != 0;
}

int hal_priv_session_state(void)
{
    peek_t pk;
    int rc = peek_open(&pk);
    if (rc == -ENOENT)
        return HAL_SESSION_NONE;
    if (rc != 0)
        return HAL_SESSION_STALE; /* damaged or foreign version */
    census_t c;
    census(pk.h, &c);
    int crashed = pk.h->rtapi_pid > 0 && !c.rtapi_alive;
    peek_close(&pk);
    if (c.rtapi_alive || c.user_alive)
        return HAL_SESSION_RUNNING;
    if (crashed || c.rt_comps || c.user_dead)
        return HAL_SESSION_STALE;
    return HAL_SESSION_IDLE;
}

int hal_priv_rt_lost(int *pid)
{
    if (hal_hdr == NULL)
        return 0;
    census_t c;
    census(hal_hdr, &c);
    if (pid != NULL)
        *pid = hal_hdr->rtapi_pid;
    return c.rt_comps > 0 && !c.rtapi_alive;
}

int hal_priv_session_rtapi_pid(void)
{
    peek_t pk;
    if (peek_open(&pk) != 0)
        return 0;
    int pid = rtapi_alive(pk.h) ? pk.h->rtapi_pid : 0;
    peek_close(&pk);
    return pid;
}

void hal_priv_session_kill(void)
{
    peek_t pk;
    if (peek_open(&pk) != 0)
        return;
    const hal_hdr_t *h = pk.h;
    int pids[256], n = 0;
    if (rtapi_alive(h))
        pids[n++] = h->rtapi_pid;
    hal_off_t off = h->comp_list;
    for (int guard = 0; off != 0 && off < h->size && guard < 100000 && n < 256; guard++) {
        const hal_comp_t *c = (const hal_comp_t *)((const char *)h + off);
        if (c->type == HAL_COMP_USER && c->pid > 0 && c->pid != getpid())
            pids[n++] = c->pid;
        off = c->next;
    }
    peek_close(&pk);
    for (int i = 0; i < n; i++)
        if (hal_priv_pid_alive(pids[i]))
            kill(pids[i], SIGTERM);
    for (int t = 0; t < 200; t++) {
        int any = 0;
        for (int i = 0; i < n; i++)
            any |= hal_priv_pid_alive(pids[i]);
        if (!any)
            return;
        usleep(10000);
    }
    for (int i = 0; i < n; i++)
        if (hal_priv_pid_alive(pids[i]))
            kill(pids[i], SIGKILL);
}

/* ---- the private runtime directory ------------------------------------------------ */

/* dir must be a real directory (not a symlink) of ours that nobody else
 * may read or write. */
static int check_private_dir(const char *dir)
{
    struct stat st;
    if (lstat(dir, &st) != 0)
        return -errno;
    if (!S_ISDIR(st.st_mode) || st.st_uid != geteuid() || (st.st_mode & 0077) != 0) {
        fprintf(stderr,
                "HAL: ERROR: runtime directory %s is not private (owner %u, mode %04o, must be "
                "a directory of uid %u with mode 0700): remove it or set XDG_RUNTIME_DIR\n",
                dir, (unsigned)st.st_uid, (unsigned)(st.st_mode & 07777), (unsigned)geteuid());
        return -EPERM;
    }
    return 0;
}

int hal_priv_runtime_dir(char *buf, size_t len, int create)
{
    const char *xdg = getenv("XDG_RUNTIME_DIR");
    struct stat st;
    int n;
    if (xdg != NULL && xdg[0] == '/' && stat(xdg, &st) == 0 && S_ISDIR(st.st_mode) &&
        st.st_uid == geteuid() && (st.st_mode & 0022) == 0)
        n = snprintf(buf, len, "%s/hm2hal", xdg);
    else
        n = snprintf(buf, len, "/tmp/hm2hal-%u", (unsigned)geteuid());
    if (n < 0 || (size_t)n >= len)
        return -ENAMETOOLONG;
    if (create && mkdir(buf, 0700) != 0 && errno != EEXIST) {
        int e = errno;
        fprintf(stderr, "HAL: ERROR: cannot create runtime directory %s: %s\n", buf,
                strerror(e));
        return -e;
    }
    return check_private_dir(buf);
}

static int log_path(char *buf, size_t len, int create)
{
    char dir[256];
    int rc = hal_priv_runtime_dir(dir, sizeof(dir), create);
    if (rc != 0)
        return rc;
    int n = snprintf(buf, len, "%s/%s.log", dir, hal_priv_shm_name() + 1);
    return (n < 0 || (size_t)n >= len) ? -ENAMETOOLONG : 0;
}

int hal_priv_open_log(char *path, size_t len)
{
    int rc = log_path(path, len, 1);
    if (rc != 0)
        return rc;
    /* Inside a directory only we can write to; still never follow a
     * link and only append to a regular file of ours. */
    int fd = open(path, O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY, 0600);
    if (fd < 0) {
        int e = errno;
        fprintf(stderr, "HAL: ERROR: cannot open log %s: %s\n", path, strerror(e));
        return -e;
    }
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_uid != geteuid()) {
        close(fd);
        fprintf(stderr, "HAL: ERROR: log %s is not a regular file of ours\n", path);
        return -EPERM;
    }
    return fd;
}

/* ---- removing a session ------------------------------------------------------------ */

int hal_priv_session_destroy(void)
{
    const char *name = hal_priv_shm_name();
    int rc = 0;
    if (shm_unlink(name) != 0 && errno != ENOENT)
        rc = -errno;
    char logname[512];
    if (log_path(logname, sizeof(logname), 0) == 0)
        unlink(logname);
    /* Other shared memory of the session: rtapi_shmem blocks (NAME-shm-KEY)
     * and the components' stream channels (NAME.sampler.N, ...). */
    char prefix[128], prefix2[128];
    snprintf(prefix, sizeof(prefix), "%s-shm-", name + 1);
    snprintf(prefix2, sizeof(prefix2), "%s.", name + 1);
    DIR *d = opendir("/dev/shm");
    if (d != NULL) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (strncmp(e->d_name, prefix, strlen(prefix)) == 0 ||
                strncmp(e->d_name, prefix2, strlen(prefix2)) == 0) {
                char n2[300];
                snprintf(n2, sizeof(n2), "/%s", e->d_name);
                shm_unlink(n2);
            }
        }
        closedir(d);
    }
    return rc;
}

int hal_priv_session_release(void)
{
    if (hal_hdr == NULL)
        return 0;
    /* A realtime host that is on its way out (nothing loaded) is waited
     * for, so `halcmd unload all` leaves nothing behind. */
    for (int t = 0; t < 2000; t++) {
        census_t c;
        census(hal_hdr, &c);
        if (!c.rtapi_alive || c.rt_comps > 0)
            break;
        usleep(1000);
    }
    hal_priv_lock();
    census_t c;
    census(hal_hdr, &c);
    int empty = !c.rtapi_alive && c.rt_comps == 0 && c.user_alive == 0 && c.user_dead == 0 &&
                c.other_comps == 0 && hal_hdr->sig_list == 0 && hal_hdr->thread_list == 0 &&
                hal_hdr->lock == 0;
    if (empty)
        hal_priv_session_destroy();
    hal_priv_unlock();
    if (empty)
        hal_priv_detach();
    return empty;
}
