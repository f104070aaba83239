/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pp_raw.c - the parallel port through raw port I/O: data, status and
 * control at base+0..2, the ECR (when there is one) at hi+2.
 *
 * I/O permission (ioperm) belongs to a thread on Linux: a thread has it if
 * it called ioperm or was created by a thread that had it.  HAL threads
 * usually exist before hal_parport loads, so every realtime function asks
 * for permission in the calling thread the first time that thread touches
 * the port (begin()), and the thread is remembered.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <sys/ioctl.h>

#include <linux/ppdev.h>

#include "pp_port.h"

#define RAW_MAX_THREADS 16
#define ECR_MODE_PS2 0x34u /* mode 001 (byte/PS2), nErrIntrEn, serviceIntr */
#define ECR_MODE_EPP 0x94u /* mode 100 (EPP) */

struct raw_priv {
    struct epp_raw_io io;
    struct epp_ppdev_sys sys;
    unsigned long base;
    long ecr;     /* ECR base (register at ecr+2), -1: none used */
    int claim_fd; /* ppdev claim held while raw I/O runs, -1 none */
    pthread_mutex_t lock; /* guards threads[]: functions of one port may run
                             in several HAL threads */
    pthread_t threads[RAW_MAX_THREADS];
    int n_threads;
};

static int grant(struct raw_priv *r)
{
    int e = r->io.ioperm(r->io.ctx, r->base, 3, 1);
    if (!e && r->ecr >= 0)
        e = r->io.ioperm(r->io.ctx, (unsigned long)r->ecr + 2, 1, 1);
    return e;
}

static int raw_begin(struct pp_port *p)
{
    struct raw_priv *r = p->priv;
    pthread_t self = pthread_self();
    int e = 0;
    pthread_mutex_lock(&r->lock);
    for (int i = 0; i < r->n_threads; i++)
        if (pthread_equal(r->threads[i], self))
            goto out;
    e = grant(r);
    if (!e && r->n_threads < RAW_MAX_THREADS)
        r->threads[r->n_threads++] = self;
out:
    pthread_mutex_unlock(&r->lock);
    return e;
}

static int raw_read_data(struct pp_port *p, uint8_t *v)
{
    struct raw_priv *r = p->priv;
    *v = r->io.inb(r->io.ctx, r->base);
    return 0;
}

static int raw_write_data(struct pp_port *p, uint8_t v)
{
    struct raw_priv *r = p->priv;
    r->io.outb(r->io.ctx, v, r->base);
    return 0;
}

static int raw_read_status(struct pp_port *p, uint8_t *v)
{
    struct raw_priv *r = p->priv;
    *v = r->io.inb(r->io.ctx, r->base + 1);
    return 0;
}

static int raw_read_control(struct pp_port *p, uint8_t *v)
{
    struct raw_priv *r = p->priv;
    *v = r->io.inb(r->io.ctx, r->base + 2);
    return 0;
}

static int raw_write_control(struct pp_port *p, uint8_t v)
{
    struct raw_priv *r = p->priv;
    r->io.outb(r->io.ctx, v, r->base + 2);
    return 0;
}

static void raw_close(struct pp_port *p)
{
    struct raw_priv *r = p->priv;
    if (!r)
        return;
    r->io.ioperm(r->io.ctx, r->base, 3, 0);
    if (r->ecr >= 0)
        r->io.ioperm(r->io.ctx, (unsigned long)r->ecr + 2, 1, 0);
    if (r->claim_fd >= 0 && r->sys.close) {
        r->sys.ioctl(r->sys.ctx, r->claim_fd, PPRELEASE, NULL);
        r->sys.close(r->sys.ctx, r->claim_fd);
    }
    pthread_mutex_destroy(&r->lock);
    free(r);
    p->priv = NULL;
}

static const struct pp_ops raw_ops = {raw_begin,      raw_read_data,      raw_write_data,
                                      raw_read_status, raw_read_control, raw_write_control,
                                      raw_close};

/* An ECR answers at ecr+2: not a floating bus (0xff), FIFO empty and not
 * full, and it keeps a mode written to it (0x34 reads back 0x35).  The old
 * value is put back. */
static int probe_ecr(struct raw_priv *r, long ecr)
{
    unsigned long a = (unsigned long)ecr + 2;
    if (r->io.ioperm(r->io.ctx, a, 1, 1))
        return 0;
    uint8_t old = r->io.inb(r->io.ctx, a);
    int ok = 0;
    if (old != 0xffu && (old & 0x03u) == 0x01u) {
        r->io.outb(r->io.ctx, 0x34u, a);
        ok = r->io.inb(r->io.ctx, a) == 0x35u;
        r->io.outb(r->io.ctx, old, a);
    }
    if (!ok)
        r->io.ioperm(r->io.ctx, a, 1, 0);
    return ok;
}

static void setup_mode(struct raw_priv *r, struct pp_port *p, long hi)
{
    if (p->mode == PP_MODE_IN || p->mode == PP_MODE_EPP) {
        long ecr = hi == 0 ? (long)r->base + 0x400 : hi;
        if (ecr > 0 && ecr <= 0xfffd && probe_ecr(r, ecr)) {
            r->ecr = ecr;
            r->io.outb(r->io.ctx, p->mode == PP_MODE_IN ? ECR_MODE_PS2 : ECR_MODE_EPP,
                       (unsigned long)ecr + 2);
        }
    }
    if (p->mode == PP_MODE_IN) {
        /* keep the control pins where they are, turn the data drivers off */
        uint8_t c = r->io.inb(r->io.ctx, r->base + 2) & 0x0fu;
        r->io.outb(r->io.ctx, (uint8_t)(c | PP_CTRL_DIR), r->base + 2);
    } else if (p->mode == PP_MODE_X)
        r->io.outb(r->io.ctx, PP_CTRL_RELEASED, r->base + 2);
}

int pp_raw_open(struct pp_port *p, const struct epp_raw_io *io, const struct epp_ppdev_sys *sys,
                unsigned long base, long hi, int claim_fd, enum pp_mode mode, char *err,
                size_t errlen)
{
    if (!io || !io->ioperm || !io->inb || !io->outb) {
        snprintf(err, errlen, "port 0x%lx: raw port I/O is not available on this machine",
                 base);
        return -ENOSYS;
    }
    struct raw_priv *r = calloc(1, sizeof(*r));
    if (!r) {
        snprintf(err, errlen, "port 0x%lx: out of memory", base);
        return -ENOMEM;
    }
    r->io = *io;
    pthread_mutex_init(&r->lock, NULL);
    if (sys)
        r->sys = *sys;
    r->base = base;
    r->ecr = -1;
    r->claim_fd = claim_fd;
    snprintf(p->name, sizeof(p->name), "0x%lx", base);
    p->kind = "raw";
    p->ops = &raw_ops;
    p->priv = r;
    p->mode = mode;
    int e = r->io.ioperm(r->io.ctx, base, 3, 1);
    if (e) {
        snprintf(err, errlen, "port 0x%lx: ioperm(0x%lx, 3) failed: %s%s", base, base,
                 strerror(-e), e == -EPERM ? " (needs root or CAP_SYS_RAWIO)" : "");
        goto fail;
    }
    r->threads[r->n_threads++] = pthread_self();
    setup_mode(r, p, hi);
    return 0;
fail:
    r->claim_fd = -1; /* the caller still owns the claim on failure */
    raw_close(p);
    return e;
}
