/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_lib.c - the rtapi.h services every HAL process shares: messages,
 * time (wall or simulated clock), rtapi_sim_yield and named shared-memory
 * blocks.  Lives in libhal so components need to link only `hal`.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "hal_priv.h"

static rtapi_msg_hook_t msg_hook;
static int local_msg_level = -1;
static __thread int in_realtime;

void rtapi_priv_set_msg_hook(rtapi_msg_hook_t hook) { msg_hook = hook; }
void rtapi_priv_set_in_realtime(int yes) { in_realtime = yes; }

static int env_msg_level(void)
{
    if (local_msg_level < 0) {
        const char *s = getenv("RTAPI_MSG_LEVEL");
        /* LinuxCNC's uspace rtapi_app shows its modules' INFO messages
         * ("hm2: loading Mesa HostMot2 driver version ..."); userspace
         * processes show errors only. */
        int lvl = hal_priv_is_realtime_host() ? RTAPI_MSG_INFO : RTAPI_MSG_ERR;
        if (s != NULL && *s) {
            char *end;
            long v = strtol(s, &end, 10);
            if (*end == '\0' && v >= RTAPI_MSG_NONE && v <= RTAPI_MSG_ALL)
                lvl = (int)v;
        }
        local_msg_level = lvl;
    }
    return local_msg_level;
}

int rtapi_get_msg_level(void)
{
    if (hal_hdr != NULL && hal_hdr->msg_level >= 0)
        return hal_hdr->msg_level;
    return env_msg_level();
}

int rtapi_set_msg_level(int level)
{
    if (level < RTAPI_MSG_NONE || level > RTAPI_MSG_ALL)
        return -EINVAL;
    local_msg_level = level;
    if (hal_hdr != NULL)
        hal_hdr->msg_level = level;
    return 0;
}

static void emit(int level, const char *fmt, va_list ap)
{
    char buf[1024];
    vsnprintf(buf, sizeof(buf), fmt, ap);
    if (msg_hook != NULL) {
        msg_hook(level, buf);
        return;
    }
    fflush(stdout);
    fputs(buf, stderr);
    fflush(stderr);
}

void rtapi_vprint_msg(msg_level_t level, const char *fmt, va_list ap)
{
    if ((int)level > rtapi_get_msg_level() && level != RTAPI_MSG_NONE)
        return;
    emit(level, fmt, ap);
}

void rtapi_print_msg(msg_level_t level, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    rtapi_vprint_msg(level, fmt, ap);
    va_end(ap);
}

void rtapi_print(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    emit(RTAPI_MSG_NONE, fmt, ap);
    va_end(ap);
}

/* ---- time ---------------------------------------------------------------- */

int rtapi_is_simclock(void)
{
    if (hal_hdr == NULL)
        hal_priv_attach();
    return hal_hdr != NULL && hal_hdr->simclock;
}

int rtapi_is_realtime(void) { return in_realtime; }

long long rtapi_get_time(void)
{
    if (hal_hdr != NULL && hal_hdr->simclock)
        return __atomic_load_n(&hal_hdr->sim_time, __ATOMIC_ACQUIRE);
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long long)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

long long rtapi_get_clocks(void)
{
#if defined(__x86_64__) || defined(__i386__)
    unsigned int lo, hi;
    __asm__ __volatile__("rdtsc" : "=a"(lo), "=d"(hi));
    return ((long long)hi << 32) | lo;
#else
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long long)ts.tv_sec * 1000000000LL + ts.tv_nsec;
#endif
}

long rtapi_delay_max(void) { return 10000; }

void rtapi_delay(long nsec)
{
    if (nsec <= 0 || (hal_hdr != NULL && hal_hdr->simclock))
        return;
    if (nsec > rtapi_delay_max())
        nsec = rtapi_delay_max();
    struct timespec t0, t;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    do {
        clock_gettime(CLOCK_MONOTONIC, &t);
    } while ((t.tv_sec - t0.tv_sec) * 1000000000L + (t.tv_nsec - t0.tv_nsec) < nsec);
}

/* The abort counter value at the start of the current simulated period,
 * set by rtapi_app's scheduler. */
static __thread uint32_t sim_abort_ref;
void rtapi_priv_sim_cycle_begin(void)
{
    if (hal_hdr != NULL)
        sim_abort_ref = __atomic_load_n(&hal_hdr->sim_abort, __ATOMIC_ACQUIRE);
}

int rtapi_sim_yield(void)
{
    if (hal_hdr == NULL || !hal_hdr->simclock)
        return 1;
    if (!hal_hdr->threads_running)
        return 1;
    if (__atomic_load_n(&hal_hdr->sim_abort, __ATOMIC_ACQUIRE) != sim_abort_ref)
        return 1;
    struct timespec ts = {0, 50000};
    nanosleep(&ts, NULL);
    return 0;
}

/* ---- named shared memory blocks ------------------------------------------- */

#define SHMEM_MAX 64
#define SHMEM_HDR 64

static struct {
    int key;
    int refs; /* handles of this process */
    size_t size;
    char *base;
} shmem_tab[SHMEM_MAX];

static void shmem_name(char *buf, size_t len, int key)
{
    snprintf(buf, len, "%s-shm-%08x", hal_priv_shm_name(), (unsigned)key);
}

int rtapi_shmem_new(int key, int module_id, unsigned long size)
{
    (void)module_id;
    if (size == 0 || size > (1ul << 30)) {
        rtapi_print_msg(RTAPI_MSG_ERR, "RTAPI: ERROR: shmem key %d: bad size %lu\n", key, size);
        return -EINVAL;
    }
    for (int i = 0; i < SHMEM_MAX; i++) {
        if (shmem_tab[i].base != NULL && shmem_tab[i].key == key) {
            if (shmem_tab[i].size != size + SHMEM_HDR) {
                rtapi_print_msg(RTAPI_MSG_ERR,
                                "RTAPI: ERROR: shmem key %d exists with another size\n", key);
                return -EINVAL;
            }
            shmem_tab[i].refs++;
            __atomic_add_fetch((int *)shmem_tab[i].base, 1, __ATOMIC_ACQ_REL);
            return i + 1;
        }
    }
    int slot = -1;
    for (int i = 0; i < SHMEM_MAX && slot < 0; i++)
        if (shmem_tab[i].base == NULL)
            slot = i;
    if (slot < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "RTAPI: ERROR: too many shmem blocks (key %d)\n", key);
        return -ENOMEM;
    }
    char name[128];
    shmem_name(name, sizeof(name), key);
    size_t total = size + SHMEM_HDR;
    int fd = shm_open(name, O_RDWR | O_CREAT | O_NOFOLLOW, 0600);
    if (fd < 0) {
        int e = errno;
        rtapi_print_msg(RTAPI_MSG_ERR, "RTAPI: ERROR: shmem key %d: %s\n", key, strerror(e));
        return -e;
    }
    struct stat st;
    /* Same access as the session's segment: private, or its HAL group. */
    long gid = (hal_hdr != NULL || hal_priv_attach() == 0) ? hal_hdr->group_gid : -1;
    if (fstat(fd, &st) == 0 && st.st_size == 0 && hal_priv_set_access(fd, gid, name) != 0) {
        close(fd);
        return -EPERM;
    }
    if (fstat(fd, &st) == 0 && st.st_size == 0 && ftruncate(fd, (off_t)total) != 0) {
        int e = errno;
        close(fd);
        rtapi_print_msg(RTAPI_MSG_ERR, "RTAPI: ERROR: shmem key %d: %s\n", key, strerror(e));
        return -e;
    }
    if (fstat(fd, &st) != 0 || (size_t)st.st_size != total) {
        close(fd);
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "RTAPI: ERROR: shmem key %d exists with another size\n", key);
        return -EINVAL;
    }
    void *p = mmap(NULL, total, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    close(fd);
    if (p == MAP_FAILED) {
        int e = errno;
        rtapi_print_msg(RTAPI_MSG_ERR, "RTAPI: ERROR: shmem key %d: %s\n", key, strerror(e));
        return -e;
    }
    __atomic_add_fetch((int *)p, 1, __ATOMIC_ACQ_REL);
    shmem_tab[slot].key = key;
    shmem_tab[slot].refs = 1;
    shmem_tab[slot].size = total;
    shmem_tab[slot].base = p;
    return slot + 1;
}

int rtapi_shmem_getptr(int handle, void **ptr)
{
    if (handle < 1 || handle > SHMEM_MAX || shmem_tab[handle - 1].base == NULL || ptr == NULL)
        return -EINVAL;
    *ptr = shmem_tab[handle - 1].base + SHMEM_HDR;
    return 0;
}

int rtapi_shmem_delete(int handle, int module_id)
{
    (void)module_id;
    if (handle < 1 || handle > SHMEM_MAX || shmem_tab[handle - 1].base == NULL)
        return -EINVAL;
    int i = handle - 1;
    int left = __atomic_sub_fetch((int *)shmem_tab[i].base, 1, __ATOMIC_ACQ_REL);
    if (--shmem_tab[i].refs == 0) {
        munmap(shmem_tab[i].base, shmem_tab[i].size);
        shmem_tab[i].base = NULL;
    }
    if (left == 0) {
        char name[128];
        shmem_name(name, sizeof(name), shmem_tab[i].key);
        shm_unlink(name);
    }
    return 0;
}
