/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _GNU_SOURCE
/* vpp_file.c - the virtual port's shared file: create, map, claim (vpp.h). */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "vpp.h"

void vpp_model_reset(struct vpp_state *st, unsigned options);

int vpp_path(const char *name, char *path, size_t len)
{
    if (!name || !*name)
        return -EINVAL;
    int n = strchr(name, '/') ? snprintf(path, len, "%s", name)
                              : snprintf(path, len, "/dev/shm/vparport.%s", name);
    return n < 0 || (size_t)n >= len ? -ENAMETOOLONG : 0;
}

static int map_fd(int fd, struct vpp_state **st)
{
    void *p = mmap(NULL, sizeof(struct vpp_state), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (p == MAP_FAILED)
        return -errno;
    *st = p;
    return 0;
}

int vpp_create(const char *name, unsigned options, int replace, char *err, size_t errlen)
{
    char path[512];
    struct vpp_state *st = NULL;
    int r = vpp_path(name, path, sizeof(path));
    if (r) {
        snprintf(err, errlen, "virtual port '%s': bad name", name ? name : "");
        return r;
    }
    if (replace && unlink(path) && errno != ENOENT) {
        r = -errno;
        snprintf(err, errlen, "virtual port %s: cannot remove the old one: %s", path,
                 strerror(-r));
        return r;
    }
    int fd = open(path, O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        r = -errno;
        snprintf(err, errlen, "virtual port %s: cannot create: %s", path, strerror(-r));
        return r;
    }
    if (ftruncate(fd, (off_t)sizeof(struct vpp_state))) {
        r = -errno;
        snprintf(err, errlen, "virtual port %s: cannot size: %s", path, strerror(-r));
        goto fail;
    }
    r = map_fd(fd, &st);
    if (r) {
        snprintf(err, errlen, "virtual port %s: cannot map: %s", path, strerror(-r));
        goto fail;
    }
    vpp_model_reset(st, options);
    st->version = VPP_VERSION;
    st->size = (uint32_t)sizeof(*st);
    __atomic_store_n(&st->magic, VPP_MAGIC, __ATOMIC_RELEASE); /* complete from here on */
    munmap(st, sizeof(*st));
    close(fd);
    return 0;
fail:
    close(fd);
    unlink(path);
    return r;
}

int vpp_remove(const char *name, char *err, size_t errlen)
{
    char path[512];
    struct vpp_state *st;
    int r = vpp_open(name, &st, err, errlen); /* only ever unlink a virtual port */
    if (r)
        return r;
    vpp_close(st);
    vpp_path(name, path, sizeof(path));
    if (unlink(path)) {
        r = -errno;
        snprintf(err, errlen, "virtual port %s: cannot remove: %s", path, strerror(-r));
        return r;
    }
    return 0;
}

int vpp_open(const char *name, struct vpp_state **out, char *err, size_t errlen)
{
    char path[512];
    struct stat sb;
    int r = vpp_path(name, path, sizeof(path));
    if (r) {
        snprintf(err, errlen, "virtual port '%s': bad name", name ? name : "");
        return r;
    }
    int fd = open(path, O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        r = -errno;
        snprintf(err, errlen, "virtual port %s: %s%s", path, strerror(-r),
                 r == -ENOENT ? " (create it with: vparport create NAME)" : "");
        return r;
    }
    if (fstat(fd, &sb) || (size_t)sb.st_size < sizeof(struct vpp_state)) {
        snprintf(err, errlen, "virtual port %s: not a virtual parallel port (size %lld)", path,
                 (long long)sb.st_size);
        close(fd);
        return -EINVAL;
    }
    struct vpp_state *st = NULL;
    r = map_fd(fd, &st);
    close(fd);
    if (r) {
        snprintf(err, errlen, "virtual port %s: cannot map: %s", path, strerror(-r));
        return r;
    }
    if (__atomic_load_n(&st->magic, __ATOMIC_ACQUIRE) != VPP_MAGIC ||
        st->version != VPP_VERSION || st->size != sizeof(*st)) {
        snprintf(err, errlen, "virtual port %s: not a virtual parallel port (bad header)", path);
        munmap(st, sizeof(*st));
        return -EINVAL;
    }
    *out = st;
    return 0;
}

void vpp_close(struct vpp_state *st)
{
    if (st)
        munmap(st, sizeof(*st));
}

int vpp_claim(struct vpp_state *st, int pid, const char *name, char *err, size_t errlen)
{
    for (;;) {
        int32_t owner = 0;
        if (__atomic_compare_exchange_n(&st->owner_pid, &owner, pid, 0, __ATOMIC_ACQ_REL,
                                        __ATOMIC_ACQUIRE))
            return 0;
        if (owner != pid && kill(owner, 0) && errno == ESRCH) {
            /* the owner died without releasing: take the claim over */
            if (__atomic_compare_exchange_n(&st->owner_pid, &owner, pid, 0, __ATOMIC_ACQ_REL,
                                            __ATOMIC_ACQUIRE))
                return 0;
            continue;
        }
        snprintf(err, errlen, "virtual port %s is busy (claimed by %s %d)", name,
                 owner == pid ? "this process," : "process", (int)owner);
        return -EBUSY;
    }
}

void vpp_release(struct vpp_state *st, int pid)
{
    int32_t expect = pid;
    __atomic_compare_exchange_n(&st->owner_pid, &expect, 0, 0, __ATOMIC_ACQ_REL,
                                __ATOMIC_ACQUIRE);
}
