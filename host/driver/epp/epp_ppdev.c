/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _GNU_SOURCE
/*
 * epp_ppdev.c - EPP through the kernel's ppdev driver (/dev/parportN):
 * PPCLAIM, PPSETMODE IEEE1284_MODE_EPP (| IEEE1284_ADDR for address
 * cycles), read()/write() for cycles, PPRSTATUS/PPWCONTROL/PPWDATA for the
 * SPP registers.  No root needed beyond access to the device node.
 *
 * The kernel's parport_pc EPP routines clear a timeout themselves and
 * return a short count, so this backend keeps the timeout bit itself: a
 * short transfer sets it, status reads report it in bit 0, a status write
 * clears it (what the drivers do to clear a timeout on a raw port).  The ECR
 * belongs to the kernel (it switches modes around its EPP transfers), so
 * ECR writes are ignored.  System calls go through a table for the tests.
 */
#include <errno.h>
#include <fcntl.h>
#include <linux/ppdev.h>
#include <linux/parport.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include "hm2/epp_port.h"

void epp_backend_delay(uint32_t ns);

struct ppdev_priv {
    struct epp_ppdev_sys sys;
    int fd;
    int mode;    /* current PPSETMODE value, -1 unknown */
    int timeout; /* sticky EPP timeout bit */
};

static int sys_open(void *ctx, const char *path, int flags)
{
    (void)ctx;
    int fd = open(path, flags);
    return fd < 0 ? -errno : fd;
}
static int sys_close(void *ctx, int fd)
{
    (void)ctx;
    return close(fd) ? -errno : 0;
}
static int sys_ioctl(void *ctx, int fd, unsigned long req, void *arg)
{
    (void)ctx;
    return ioctl(fd, req, arg) < 0 ? -errno : 0;
}
static long sys_read(void *ctx, int fd, void *buf, size_t n)
{
    (void)ctx;
    ssize_t r = read(fd, buf, n);
    return r < 0 ? -errno : (long)r;
}
static long sys_write(void *ctx, int fd, const void *buf, size_t n)
{
    (void)ctx;
    ssize_t r = write(fd, buf, n);
    return r < 0 ? -errno : (long)r;
}
const struct epp_ppdev_sys epp_ppdev_sys_libc = {sys_open, sys_close, sys_ioctl, sys_read,
                                                 sys_write, NULL};

static int set_mode(struct ppdev_priv *p, int mode)
{
    if (p->mode == mode)
        return 0;
    int r = p->sys.ioctl(p->sys.ctx, p->fd, PPSETMODE, &mode);
    if (r)
        return r;
    p->mode = mode;
    return 0;
}

/* One read/write of n bytes; a short count (or EAGAIN/EIO) is the kernel
 * telling us the peripheral did not complete a cycle: an EPP timeout. */
static int xfer(struct ppdev_priv *p, int mode, int is_read, uint8_t *buf, size_t n)
{
    int r = set_mode(p, mode);
    if (r)
        return r;
    if (p->timeout) {
        /* A PC port stops doing cycles while the timeout bit is set. */
        if (is_read)
            memset(buf, 0xFF, n);
        return 0;
    }
    long got = is_read ? p->sys.read(p->sys.ctx, p->fd, buf, n)
                       : p->sys.write(p->sys.ctx, p->fd, buf, n);
    if (got == (long)n)
        return 0;
    if (got >= 0 || got == -EIO || got == -EAGAIN || got == -ETIMEDOUT) {
        if (is_read && got >= 0)
            memset(buf + got, 0xFF, n - (size_t)got);
        else if (is_read)
            memset(buf, 0xFF, n);
        p->timeout = 1;
        return 0;
    }
    return (int)got;
}

static int ppdev_execute(epp_port_t *port, const struct epp_op *ops, size_t n)
{
    struct ppdev_priv *p = port->priv;
    int r = 0;
    for (size_t i = 0; i < n && !r; i++) {
        const struct epp_op *op = &ops[i];
        uint8_t v;
        int iv;
        switch (op->kind) {
        case EPP_OP_ADDR_WRITE:
            v = (uint8_t)op->val;
            r = xfer(p, IEEE1284_MODE_EPP | IEEE1284_ADDR, 0, &v, 1);
            break;
        case EPP_OP_ADDR_READ:
            r = xfer(p, IEEE1284_MODE_EPP | IEEE1284_ADDR, 1, op->buf, 1);
            break;
        case EPP_OP_DATA_WRITE:
            r = xfer(p, IEEE1284_MODE_EPP, 0, op->buf, op->n);
            break;
        case EPP_OP_DATA_READ:
            r = xfer(p, IEEE1284_MODE_EPP, 1, op->buf, op->n);
            break;
        case EPP_OP_STATUS_READ:
            r = p->sys.ioctl(p->sys.ctx, p->fd, PPRSTATUS, &v);
            if (!r)
                op->buf[0] = (uint8_t)((v & 0xFEu) | (p->timeout ? EPP_STATUS_TIMEOUT : 0));
            break;
        case EPP_OP_STATUS_WRITE:
            p->timeout = 0;
            break;
        case EPP_OP_CONTROL_WRITE:
            v = (uint8_t)op->val;
            r = p->sys.ioctl(p->sys.ctx, p->fd, PPWCONTROL, &v);
            break;
        case EPP_OP_SPP_DATA_WRITE:
            v = (uint8_t)op->val;
            iv = 0; /* data lines driven by the host */
            r = p->sys.ioctl(p->sys.ctx, p->fd, PPDATADIR, &iv);
            if (!r)
                r = p->sys.ioctl(p->sys.ctx, p->fd, PPWDATA, &v);
            break;
        case EPP_OP_ECR_WRITE:
            break;
        case EPP_OP_DELAY:
            epp_backend_delay(op->val);
            break;
        default:
            r = -EINVAL;
        }
    }
    return r;
}

static void ppdev_close(epp_port_t *port)
{
    struct ppdev_priv *p = port->priv;
    if (!p)
        return;
    p->sys.ioctl(p->sys.ctx, p->fd, PPRELEASE, NULL);
    p->sys.close(p->sys.ctx, p->fd);
    free(p);
}

static const struct epp_backend ppdev_backend = {"ppdev", 0, ppdev_execute, ppdev_close};

int epp_ppdev_open(epp_port_t *port, const struct epp_ppdev_sys *sys, const char *path, int wide,
                   char *err, size_t errlen)
{
    int fd, r, mode;
    struct ppdev_priv *p;

    if (!sys || !path || !*path) {
        snprintf(err, errlen, "ppdev: no device path");
        return -EINVAL;
    }
    fd = sys->open(sys->ctx, path, O_RDWR);
    if (fd < 0) {
        snprintf(err, errlen, "ppdev %s: open failed: %s", path, strerror(-fd));
        return fd;
    }
    r = sys->ioctl(sys->ctx, fd, PPCLAIM, NULL);
    if (r) {
        snprintf(err, errlen, "ppdev %s: PPCLAIM failed: %s (port busy?)", path, strerror(-r));
        goto fail_close;
    }
    mode = IEEE1284_MODE_EPP;
    r = sys->ioctl(sys->ctx, fd, PPSETMODE, &mode);
    if (r) {
        snprintf(err, errlen, "ppdev %s: PPSETMODE EPP failed: %s (port without EPP?)", path,
                 strerror(-r));
        goto fail_release;
    }
    if (wide) {
        int flags = PP_FASTWRITE | PP_FASTREAD;
        r = sys->ioctl(sys->ctx, fd, PPSETFLAGS, &flags);
        if (r) {
            snprintf(err, errlen, "ppdev %s: PPSETFLAGS (wide EPP) failed: %s", path,
                     strerror(-r));
            goto fail_release;
        }
    }
    p = calloc(1, sizeof(*p));
    if (!p) {
        r = -ENOMEM;
        snprintf(err, errlen, "ppdev %s: out of memory", path);
        goto fail_release;
    }
    p->sys = *sys;
    p->fd = fd;
    p->mode = mode;
    char name[64];
    snprintf(name, sizeof(name), "ppdev:%s", path);
    epp_port_init(port, &ppdev_backend, p, name, wide);
    port->has_ecr = 0;
    return 0;

fail_release:
    sys->ioctl(sys->ctx, fd, PPRELEASE, NULL);
fail_close:
    sys->close(sys->ctx, fd);
    return r;
}

/* ---- the ppdev:DEVICE port kind ---- */

static int ppdev_open_spec(epp_port_t *port, const char *arg, const char *spec, int wide,
                           char *err, size_t errlen)
{
    if (!*arg) {
        snprintf(err, errlen, "port '%s': missing device path (ppdev:/dev/parport0)", spec);
        return -EINVAL;
    }
    return epp_ppdev_open(port, &epp_ppdev_sys_libc, arg, wide, err, errlen);
}

const struct epp_port_kind epp_ppdev_kind = {"ppdev", "ppdev:DEV", ppdev_open_spec};
