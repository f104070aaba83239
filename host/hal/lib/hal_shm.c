/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_shm.c - the session's shared-memory segment: naming (HAL_INSTANCE,
 * HAL_OWNER), access rights (private, or shared with HAL_GROUP),
 * creation/attachment and the one robust mutex.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <pwd.h>
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

/* Owner of the session: HAL_OWNER (a user name or uid, for joining a
 * session another user shares through HAL_GROUP), else ourselves. */
uid_t hal_priv_owner_uid(void)
{
    const char *o = getenv("HAL_OWNER");
    if (o == NULL || o[0] == '\0')
        return getuid();
    char *end;
    unsigned long v = strtoul(o, &end, 10);
    if (*end == '\0')
        return (uid_t)v;
    struct passwd *pw = getpwnam(o);
    return pw != NULL ? pw->pw_uid : (uid_t)-1;
}

/* The group named by HAL_GROUP, -1 when unset, -2 when it does not exist. */
long hal_priv_group_gid(void)
{
    const char *g = getenv("HAL_GROUP");
    if (g == NULL || g[0] == '\0')
        return -1;
    char *end;
    unsigned long v = strtoul(g, &end, 10);
    if (*end == '\0')
        return (long)v;
    struct group *gr = getgrnam(g);
    return gr != NULL ? (long)gr->gr_gid : -2;
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
    snprintf(shm_name_buf, sizeof(shm_name_buf), "/hm2hal-%u-%s",
             (unsigned)hal_priv_owner_uid(), clean);
    return shm_name_buf;
}

void hal_priv_socket_name(char *buf, size_t len)
{
    /* Abstract unix socket: leading NUL, vanishes with its process.  It
     * has no file permissions: rtapi_app checks each peer (SO_PEERCRED). */
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

int hal_priv_set_access(int fd, long gid, const char *what)
{
    /* Explicit modes: a umask of 000 must not make anything world
     * writable, one of 077 must not lock the group out. */
    if (gid >= 0) {
        if (fchown(fd, (uid_t)-1, (gid_t)gid) != 0 || fchmod(fd, 0660) != 0) {
            int e = errno;
            fprintf(stderr, "HAL: ERROR: cannot give group %ld access to %s: %s\n", gid, what,
                    strerror(e));
            return -e;
        }
        return 0;
    }
    if (fchmod(fd, 0600) != 0) {
        int e = errno;
        fprintf(stderr, "HAL: ERROR: cannot make %s private: %s\n", what, strerror(e));
        return -e;
    }
    return 0;
}

static int init_segment(char *base, size_t size, long gid)
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
    h->owner_uid = (uint32_t)hal_priv_owner_uid();
    h->group_gid = (int32_t)gid;
    h->version = HAL_SHM_VERSION;
    __atomic_store_n(&h->magic, HAL_SHM_MAGIC, __ATOMIC_RELEASE);
    return 0;
}

/* Create the segment; fd >= 0, or -errno (-EEXIST: someone else did). */
static int create_segment(const char *name, size_t size, long gid)
{
    int fd = shm_open(name, O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW, 0600);
    if (fd < 0)
        return -errno;
    int rc = hal_priv_set_access(fd, gid, name);
    if (rc == 0 && ftruncate(fd, (off_t)size) != 0) {
        rc = -errno;
        fprintf(stderr, "HAL: ERROR: cannot size shared memory %s: %s\n", name, strerror(-rc));
    }
    if (rc != 0) {
        close(fd);
        shm_unlink(name);
        return rc;
    }
    return fd;
}

/* Open an existing segment; fd >= 0 with *size set, or -errno. */
static int open_segment(const char *name, size_t *size)
{
    int fd = shm_open(name, O_RDWR | O_NOFOLLOW, 0600);
    if (fd < 0) {
        int e = errno;
        if (e == EACCES)
            fprintf(stderr,
                    "HAL: ERROR: HAL session %s belongs to another user (see HAL_GROUP in "
                    "docs/hal.md)\n",
                    name);
        else
            fprintf(stderr, "HAL: ERROR: cannot open shared memory %s: %s\n", name,
                    strerror(e));
        return -e;
    }
    struct stat st;
    /* The creator may still be sizing it. */
    for (int i = 0; i < 1000; i++) {
        if (fstat(fd, &st) == 0 && st.st_size > 0)
            break;
        usleep(1000);
    }
    if ((size_t)st.st_size < sizeof(hal_hdr_t)) {
        close(fd);
        fprintf(stderr, "HAL: ERROR: shared memory %s is truncated\n", name);
        return -EINVAL;
    }
    *size = (size_t)st.st_size;
    return fd;
}

int hal_priv_attach(void)
{
    if (hal_shmem_base != NULL)
        return 0;
    const char *name = hal_priv_shm_name();
    size_t size = shm_size_from_env();
    long gid = hal_priv_group_gid();
    if (gid == -2) {
        fprintf(stderr, "HAL: ERROR: HAL_GROUP '%s' is not a group\n", getenv("HAL_GROUP"));
        return -EINVAL;
    }
    int created = 1;
    int fd = create_segment(name, size, gid);
    if (fd == -EEXIST) {
        created = 0;
        fd = open_segment(name, &size);
    } else if (fd < 0 && fd != -EACCES) {
        fprintf(stderr, "HAL: ERROR: cannot create shared memory %s: %s\n", name, strerror(-fd));
    }
    if (fd < 0)
        return fd;
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
        int rc = init_segment(p, size, gid);
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

void hal_priv_detach(void)
{
    if (hal_shmem_base == NULL)
        return;
    munmap(hal_shmem_base, hal_hdr->size);
    hal_shmem_base = NULL;
    hal_hdr = NULL;
}
