/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _GNU_SOURCE
/*
 * epp_raw.c - EPP through raw port I/O (ioperm + in/out instructions), the
 * lowest-latency path and the one LinuxCNC's drivers use: base+3 address
 * port, base+4 data port (16/32-bit I/O in wide mode), base+1 status with
 * bit 0 = timeout, ECR at base_hi+2.  The instructions go through a small
 * table so the unit tests can put a simulated port behind it.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hm2/epp_port.h"

#if defined(__x86_64__) || defined(__i386__)
#include <sys/io.h>
#define EPP_HAVE_PORT_IO 1
#endif

struct raw_priv {
    struct epp_raw_io io;
    unsigned long base;
    long base_hi; /* -1: no ECR */
};

/* ---- the real instructions ---------------------------------------------- */

#ifdef EPP_HAVE_PORT_IO
static int sys_ioperm(void *ctx, unsigned long from, unsigned long num, int on)
{
    (void)ctx;
    return ioperm(from, num, on) ? -errno : 0;
}
static uint8_t sys_inb(void *ctx, unsigned long port)
{
    (void)ctx;
    return inb((unsigned short)port);
}
static uint16_t sys_inw(void *ctx, unsigned long port)
{
    (void)ctx;
    return inw((unsigned short)port);
}
static uint32_t sys_inl(void *ctx, unsigned long port)
{
    (void)ctx;
    return inl((unsigned short)port);
}
static void sys_outb(void *ctx, uint8_t v, unsigned long port)
{
    (void)ctx;
    outb(v, (unsigned short)port);
}
static void sys_outw(void *ctx, uint16_t v, unsigned long port)
{
    (void)ctx;
    outw(v, (unsigned short)port);
}
static void sys_outl(void *ctx, uint32_t v, unsigned long port)
{
    (void)ctx;
    outl(v, (unsigned short)port);
}
const struct epp_raw_io epp_raw_sys_io = {sys_ioperm, sys_inb, sys_inw, sys_inl,
                                          sys_outb,   sys_outw, sys_outl, NULL};
#else
static int sys_ioperm(void *ctx, unsigned long from, unsigned long num, int on)
{
    (void)ctx, (void)from, (void)num, (void)on;
    return -ENOSYS;
}
const struct epp_raw_io epp_raw_sys_io = {sys_ioperm, NULL, NULL, NULL, NULL, NULL, NULL, NULL};
#endif

/* ---- delay -------------------------------------------------------------- */

static uint64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Short waits spin (a sleep would be far longer than asked); long ones
 * sleep.  Shared with the other direct backends. */
void epp_backend_delay(uint32_t ns);
void epp_backend_delay(uint32_t ns)
{
    if (ns >= 100000) {
        struct timespec ts = {.tv_sec = ns / 1000000000u, .tv_nsec = ns % 1000000000u};
        while (nanosleep(&ts, &ts) != 0 && errno == EINTR)
            ;
        return;
    }
    uint64_t end = mono_ns() + ns;
    while (mono_ns() < end)
        ;
}

/* ---- execute ------------------------------------------------------------ */

static int raw_execute(epp_port_t *port, const struct epp_op *ops, size_t n)
{
    struct raw_priv *p = port->priv;
    const struct epp_raw_io *io = &p->io;
    unsigned long b = p->base;
    for (size_t i = 0; i < n; i++) {
        const struct epp_op *op = &ops[i];
        uint32_t k;
        switch (op->kind) {
        case EPP_OP_ADDR_WRITE:
            io->outb(io->ctx, (uint8_t)op->val, b + 3);
            break;
        case EPP_OP_ADDR_READ:
            op->buf[0] = io->inb(io->ctx, b + 3);
            break;
        case EPP_OP_DATA_WRITE:
            for (k = 0; k < op->n; k += op->width) {
                const uint8_t *d = op->buf + k;
                if (op->width == 4)
                    io->outl(io->ctx,
                             (uint32_t)d[0] | (uint32_t)d[1] << 8 | (uint32_t)d[2] << 16 |
                                 (uint32_t)d[3] << 24,
                             b + 4);
                else if (op->width == 2)
                    io->outw(io->ctx, (uint16_t)(d[0] | d[1] << 8), b + 4);
                else
                    io->outb(io->ctx, d[0], b + 4);
            }
            break;
        case EPP_OP_DATA_READ:
            for (k = 0; k < op->n; k += op->width) {
                uint8_t *d = op->buf + k;
                if (op->width == 4) {
                    uint32_t v = io->inl(io->ctx, b + 4);
                    d[0] = (uint8_t)v, d[1] = (uint8_t)(v >> 8), d[2] = (uint8_t)(v >> 16),
                    d[3] = (uint8_t)(v >> 24);
                } else if (op->width == 2) {
                    uint16_t v = io->inw(io->ctx, b + 4);
                    d[0] = (uint8_t)v, d[1] = (uint8_t)(v >> 8);
                } else {
                    d[0] = io->inb(io->ctx, b + 4);
                }
            }
            break;
        case EPP_OP_STATUS_READ:
            op->buf[0] = io->inb(io->ctx, b + 1);
            break;
        case EPP_OP_STATUS_WRITE:
            io->outb(io->ctx, (uint8_t)op->val, b + 1);
            break;
        case EPP_OP_CONTROL_WRITE:
            io->outb(io->ctx, (uint8_t)op->val, b + 2);
            break;
        case EPP_OP_SPP_DATA_WRITE:
            io->outb(io->ctx, (uint8_t)op->val, b + 0);
            break;
        case EPP_OP_ECR_WRITE:
            if (p->base_hi >= 0)
                io->outb(io->ctx, (uint8_t)op->val, (unsigned long)p->base_hi + 2);
            break;
        case EPP_OP_DELAY:
            epp_backend_delay(op->val);
            break;
        default:
            return -EINVAL;
        }
    }
    return 0;
}

static void raw_close(epp_port_t *port)
{
    struct raw_priv *p = port->priv;
    if (!p)
        return;
    p->io.ioperm(p->io.ctx, p->base, 8, 0);
    if (p->base_hi >= 0)
        p->io.ioperm(p->io.ctx, (unsigned long)p->base_hi, 4, 0);
    free(p);
}

static const struct epp_backend raw_backend = {"raw", 0, raw_execute, raw_close};

int epp_raw_open(epp_port_t *port, const struct epp_raw_io *io, unsigned long base, long base_hi,
                 int wide, char *err, size_t errlen)
{
    int r;
    if (!io || !io->ioperm || base == 0 || base > 0xFFF8 || base_hi > 0xFFFC) {
        snprintf(err, errlen, "raw port 0x%lx: bad I/O address", base);
        return -EINVAL;
    }
    r = io->ioperm(io->ctx, base, 8, 1);
    if (r) {
        snprintf(err, errlen, "raw port 0x%lx: ioperm(0x%lx, 8) failed: %s (needs root or "
                              "CAP_SYS_RAWIO)", base, base, strerror(-r));
        return r;
    }
    if (base_hi >= 0) {
        r = io->ioperm(io->ctx, (unsigned long)base_hi, 4, 1);
        if (r) {
            snprintf(err, errlen, "raw port 0x%lx: ioperm(0x%lx, 4) for the ECR failed: %s",
                     base, (unsigned long)base_hi, strerror(-r));
            io->ioperm(io->ctx, base, 8, 0);
            return r;
        }
    }
    struct raw_priv *p = calloc(1, sizeof(*p));
    if (!p) {
        io->ioperm(io->ctx, base, 8, 0);
        snprintf(err, errlen, "raw port 0x%lx: out of memory", base);
        return -ENOMEM;
    }
    p->io = *io;
    p->base = base;
    p->base_hi = base_hi;
    char name[48];
    snprintf(name, sizeof(name), "raw:0x%lx", base);
    epp_port_init(port, &raw_backend, p, name, wide);
    port->base = base;
    port->base_hi = base_hi >= 0 ? (unsigned long)base_hi : 0;
    port->has_ecr = base_hi >= 0;
    return 0;
}

/* ---- the raw:ADDR[,ECR] port kind ---- */

static int parse_ulong(const char *s, unsigned long *out)
{
    char *end;
    if (!s || !*s)
        return -EINVAL;
    errno = 0;
    unsigned long v = strtoul(s, &end, 0);
    if (errno || *end || s[0] == '-')
        return -EINVAL;
    *out = v;
    return 0;
}

static int raw_open_spec(epp_port_t *port, const char *arg, const char *spec, int wide, char *err,
                         size_t errlen)
{
    unsigned long base, hi;
    char tmp[64];
    snprintf(tmp, sizeof(tmp), "%s", arg);
    char *comma = strchr(tmp, ',');
    if (comma)
        *comma++ = '\0';
    if (parse_ulong(tmp, &base) || base == 0 || base > 0xFFFF) {
        snprintf(err, errlen, "port '%s': bad I/O address '%s'", spec, tmp);
        return -EINVAL;
    }
    long hi_arg = (long)base + 0x400;
    if (comma) {
        if (strcmp(comma, "none") == 0 || strcmp(comma, "-1") == 0) {
            hi_arg = -1;
        } else if (parse_ulong(comma, &hi) || hi > 0xFFFF) {
            snprintf(err, errlen, "port '%s': bad ECR base '%s'", spec, comma);
            return -EINVAL;
        } else {
            hi_arg = hi ? (long)hi : (long)base + 0x400;
        }
    }
    return epp_raw_open(port, &epp_raw_sys_io, base, hi_arg, wide, err, errlen);
}

const struct epp_port_kind epp_raw_kind = {"raw", "raw:ADDR", raw_open_spec};
