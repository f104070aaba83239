/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_shm.c - the session's shared-memory segment: naming (HAL_INSTANCE),
 * creation/attachment, the one robust mutex, the bump allocators and the
 * session liveness check used by halrun.
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

char *hal_shmem_base;
hal_hdr_t *hal_hdr;

static char shm_name_buf[96];

const char *hal_priv_instance(void)
{
    const char *inst = getenv("HAL_INSTANCE");
    if (inst == NULL || inst[0] == '\0')
        return "0";
    return inst;
}

const char *hal_priv_shm_name(void)
{
    /* The instance string is user input: keep only characters that are
     * safe in a shm name. */
    const char *inst = hal_priv_instance();
    char clean[64];
    size_t n = 0;
    for (const char *p = inst; *p && n < sizeof(clean) - 1; p++)
        clean[n++] = (*p == '/') ? '_' : *p;
    clean[n] = '\0';
    snprintf(shm_name_buf, sizeof(shm_name_buf), "/hm2hal-%u-%s", (unsigned)getuid(), clean);
    return shm_name_buf;
}

void hal_priv_socket_name(char *buf, size_t len)
{
    /* Abstract unix socket: leading NUL, vanishes with its process. */
    const char *shm = hal_priv_shm_name();
    if (len < 2)
        return;
    buf[0] = '\0';
    snprintf(buf + 1, len - 1, "%s.rtapi", shm + 1);
}

static size_t shm_size_from_env(void)
{
    const char *s = getenv("HAL_SHMEM_SIZE");
    if (s != NULL && *s) {
        char *end;
        unsigned long v = strtoul(s, &end, 0);
        if (*end == '\0' && v >= 65536 && v <= (1ul << 30))
            return (size_t)v;
    }
    return HAL_DEFAULT_SHM_SIZE;
}

static int env_simclock(void)
{
    const char *s = getenv("HAL_SIMCLOCK");
    return s != NULL && s[0] != '\0' && strcmp(s, "0") != 0;
}

static int init_segment(char *base, size_t size)
{
    hal_hdr_t *h = (hal_hdr_t *)base;
    memset(h, 0, sizeof(*h));
    pthread_mutexattr_t attr;
    pthread_mutexattr_init(&attr);
    pthread_mutexattr_setpshared(&attr, PTHREAD_PROCESS_SHARED);
    pthread_mutexattr_setrobust(&attr, PTHREAD_MUTEX_ROBUST);
    int rc = pthread_mutex_init(&h->mutex, &attr);
    pthread_mutexattr_destroy(&attr);
    if (rc != 0)
        return -rc;
    h->size = (uint32_t)size;
    h->hdr_size = (uint32_t)((sizeof(*h) + 63) & ~(size_t)63);
    h->bot = h->hdr_size;
    h->top = (uint32_t)size;
    for (int i = 0; i < 6; i++) {
        h->idx[i] = h->bot;
        memset(base + h->bot, 0, HAL_HASH_SIZE * sizeof(hal_off_t));
        h->bot += HAL_HASH_SIZE * sizeof(hal_off_t);
    }
    /* id 1 is the session itself (LinuxCNC's rtapi master takes it). */
    h->next_id = 2;
    h->msg_level = -1;
    h->simclock = env_simclock();
    h->version = HAL_SHM_VERSION;
    __atomic_store_n(&h->magic, HAL_SHM_MAGIC, __ATOMIC_RELEASE);
    return 0;
}

int hal_priv_attach(void)
{
    if (hal_shmem_base != NULL)
        return 0;
    const char *name = hal_priv_shm_name();
    size_t size = shm_size_from_env();
    int created = 0;
    int fd = shm_open(name, O_RDWR | O_CREAT | O_EXCL, 0600);
    if (fd >= 0) {
        created = 1;
        if (ftruncate(fd, (off_t)size) != 0) {
            int e = errno;
            close(fd);
            shm_unlink(name);
            fprintf(stderr, "HAL: ERROR: cannot size shared memory %s: %s\n", name, strerror(e));
            return -e;
        }
    } else if (errno == EEXIST) {
        fd = shm_open(name, O_RDWR, 0600);
        if (fd < 0) {
            int e = errno;
            fprintf(stderr, "HAL: ERROR: cannot open shared memory %s: %s\n", name, strerror(e));
            return -e;
        }
        struct stat st;
        /* The creator may still be sizing it. */
        for (int i = 0; i < 1000; i++) {
            if (fstat(fd, &st) == 0 && st.st_size > 0)
                break;
            usleep(1000);
        }
        size = (size_t)st.st_size;
        if (size < sizeof(hal_hdr_t)) {
            close(fd);
            fprintf(stderr, "HAL: ERROR: shared memory %s is truncated\n", name);
            return -EINVAL;
        }
    } else {
        int e = errno;
        fprintf(stderr, "HAL: ERROR: cannot create shared memory %s: %s\n", name, strerror(e));
        return -e;
    }
    void *p = mmap(NULL, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    int e = errno;
    close(fd);
    if (p == MAP_FAILED) {
        fprintf(stderr, "HAL: ERROR: cannot map shared memory %s: %s\n", name, strerror(e));
        if (created)
            shm_unlink(name);
        return -e;
    }
    hal_hdr_t *h = p;
    if (created) {
        int rc = init_segment(p, size);
        if (rc < 0) {
            munmap(p, size);
            shm_unlink(name);
            return rc;
        }
    } else {
        for (int i = 0; i < 1000 && __atomic_load_n(&h->magic, __ATOMIC_ACQUIRE) == 0; i++)
            usleep(1000);
        if (h->magic != HAL_SHM_MAGIC || h->version != HAL_SHM_VERSION || h->size != size) {
            munmap(p, size);
            fprintf(stderr,
                    "HAL: ERROR: shared memory %s has a wrong version or size "
                    "(stale session? run 'halrun -U')\n",
                    name);
            return -EINVAL;
        }
    }
    hal_shmem_base = p;
    hal_hdr = h;
    return 0;
}

void hal_priv_lock(void)
{
    int rc = pthread_mutex_lock(&hal_hdr->mutex);
    if (rc == EOWNERDEAD) {
        /* A process died holding the lock; the structures are updated in
         * an order that keeps lists walkable, so carry on. */
        pthread_mutex_consistent(&hal_hdr->mutex);
    }
}

void hal_priv_unlock(void) { pthread_mutex_unlock(&hal_hdr->mutex); }

void hal_priv_force_unlock(void)
{
    if (hal_hdr == NULL)
        return;
    /* Re-initialise the mutex: only for crash recovery (halcmd -R). */
    pthread_mutexattr_t attr;
    pthread_mutexattr_init(&attr);
    pthread_mutexattr_setpshared(&attr, PTHREAD_PROCESS_SHARED);
    pthread_mutexattr_setrobust(&attr, PTHREAD_MUTEX_ROBUST);
    pthread_mutex_init(&hal_hdr->mutex, &attr);
    pthread_mutexattr_destroy(&attr);
}

/* Alive and not a zombie (a killed rtapi_app may stay a zombie for a
 * while when its reaper is slow). */
int hal_priv_pid_alive(int pid)
{
    if (pid <= 0)
        return 0;
    if (kill(pid, 0) != 0 && errno != EPERM)
        return 0;
    char path[64], buf[256];
    snprintf(path, sizeof(path), "/proc/%d/stat", pid);
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return 1;
    size_t n = fread(buf, 1, sizeof(buf) - 1, f);
    fclose(f);
    buf[n] = '\0';
    const char *rp = strrchr(buf, ')');
    return !(rp != NULL && rp[1] == ' ' && rp[2] == 'Z');
}

int hal_priv_session_state(void)
{
    const char *name = hal_priv_shm_name();
    int fd = shm_open(name, O_RDWR, 0600);
    if (fd < 0)
        return 0;
    struct stat st;
    if (fstat(fd, &st) != 0 || (size_t)st.st_size < sizeof(hal_hdr_t)) {
        close(fd);
        return 2;
    }
    void *p = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_SHARED, fd, 0);
    close(fd);
    if (p == MAP_FAILED)
        return 2;
    const hal_hdr_t *h = p;
    int alive = 0;
    if (h->magic == HAL_SHM_MAGIC && h->version == HAL_SHM_VERSION &&
        h->size == (uint32_t)st.st_size) {
        if (hal_priv_pid_alive(h->rtapi_pid))
            alive = 1;
        /* Without the lock (it may be held by a dead process): the lists
         * are only walked to look for a live user component. */
        hal_off_t off = h->comp_list;
        for (int guard = 0; off != 0 && off < h->size && guard < 100000; guard++) {
            const hal_comp_t *c = (const hal_comp_t *)((const char *)p + off);
            if (c->type == HAL_COMP_USER && c->pid != getpid() && hal_priv_pid_alive(c->pid))
                alive = 1;
            off = c->next;
        }
    }
    munmap(p, (size_t)st.st_size);
    return alive ? 1 : 2;
}

int hal_priv_session_rtapi_pid(void)
{
    int fd = shm_open(hal_priv_shm_name(), O_RDONLY, 0600);
    if (fd < 0)
        return 0;
    struct stat st;
    int pid = 0;
    if (fstat(fd, &st) == 0 && (size_t)st.st_size >= sizeof(hal_hdr_t)) {
        void *p = mmap(NULL, sizeof(hal_hdr_t), PROT_READ, MAP_SHARED, fd, 0);
        if (p != MAP_FAILED) {
            const hal_hdr_t *h = p;
            if (h->magic == HAL_SHM_MAGIC)
                pid = h->rtapi_pid;
            munmap(p, sizeof(hal_hdr_t));
        }
    }
    close(fd);
    return pid;
}

void hal_priv_session_kill(void)
{
    const char *name = hal_priv_shm_name();
    int fd = shm_open(name, O_RDWR, 0600);
    if (fd < 0)
        return;
    struct stat st;
    if (fstat(fd, &st) != 0 || (size_t)st.st_size < sizeof(hal_hdr_t)) {
        close(fd);
        return;
    }
    void *p = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_SHARED, fd, 0);
    close(fd);
    if (p == MAP_FAILED)
        return;
    const hal_hdr_t *h = p;
    int pids[256], n = 0;
    if (h->magic == HAL_SHM_MAGIC && h->size == (uint32_t)st.st_size) {
        if (h->rtapi_pid > 0)
            pids[n++] = h->rtapi_pid;
        hal_off_t off = h->comp_list;
        for (int guard = 0; off != 0 && off < h->size && guard < 100000 && n < 256; guard++) {
            const hal_comp_t *c = (const hal_comp_t *)((const char *)p + off);
            if (c->type == HAL_COMP_USER && c->pid > 0 && c->pid != getpid())
                pids[n++] = c->pid;
            off = c->next;
        }
    }
    munmap(p, (size_t)st.st_size);
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

int hal_priv_session_destroy(void)
{
    const char *name = hal_priv_shm_name();
    int rc = 0;
    if (shm_unlink(name) != 0 && errno != ENOENT)
        rc = -errno;
    /* rtapi_app's log when it ran without a terminal (rtapi_client.c) */
    char logname[256];
    snprintf(logname, sizeof(logname), "/tmp%s.log", name);
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
