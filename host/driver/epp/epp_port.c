/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _GNU_SOURCE
/*
 * epp_port.c - the epp_port queue, counters and backend selection
 * (docs/epp_port.md).  Backends only execute lists of operations; all the
 * bookkeeping lives here so every backend counts cycles the same way.
 */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hm2/epp_port.h"

#define EPP_INITIAL_OPS 64
#define EPP_INITIAL_POOL 256
/* Upper bounds so a runaway caller gets -ENOMEM instead of eating memory
 * (a 7i43 bitstream is ~200 KB of byte writes: ~1 op each is not needed,
 * they are one op per call, but allow large pools). */
#define EPP_MAX_OPS (1u << 22)
#define EPP_MAX_POOL (64u << 20)

void epp_port_init(epp_port_t *port, const struct epp_backend *backend, void *priv,
                   const char *name, int wide)
{
    memset(port, 0, sizeof(*port));
    port->backend = backend;
    port->priv = priv;
    port->wide = wide ? 1 : 0;
    port->cycle_ns = 1000;
    port->reg_ns = 1000;
    snprintf(port->name, sizeof(port->name), "%s", name ? name : backend->kind);
}

void epp_port_set_timing(epp_port_t *port, uint32_t cycle_ns, uint32_t reg_ns)
{
    port->cycle_ns = cycle_ns;
    port->reg_ns = reg_ns;
}

void epp_counters_reset(epp_port_t *port)
{
    memset(&port->count, 0, sizeof(port->count));
}

static int grow(void **p, size_t *cap, size_t need, size_t elem, size_t initial, size_t max)
{
    if (need <= *cap)
        return 0;
    size_t n = *cap ? *cap : initial;
    while (n < need)
        n *= 2;
    if (n > max)
        return -ENOMEM;
    void *q = realloc(*p, n * elem);
    if (!q)
        return -ENOMEM;
    *p = q;
    *cap = n;
    return 0;
}

void epp_discard(epp_port_t *port)
{
    port->n_ops = 0;
    port->n_pool = 0;
}

static void account(epp_port_t *port, const struct epp_op *op)
{
    struct epp_counters *c = &port->count;
    switch (op->kind) {
    case EPP_OP_ADDR_WRITE:
    case EPP_OP_ADDR_READ:
        c->addr_cycles++;
        c->port_ios++;
        c->bus_ns += port->cycle_ns;
        break;
    case EPP_OP_DATA_WRITE:
    case EPP_OP_DATA_READ:
        c->data_cycles += op->n;
        if (op->kind == EPP_OP_DATA_READ)
            c->data_reads += op->n;
        c->port_ios += op->n / op->width;
        c->bus_ns += (uint64_t)op->n * port->cycle_ns;
        break;
    case EPP_OP_DELAY:
        break;
    default:
        c->reg_accesses++;
        c->port_ios++;
        c->bus_ns += port->reg_ns;
        break;
    }
}

/* Queue one op; a non-batching backend runs it at once. */
static int push(epp_port_t *port, struct epp_op op, const void *wdata)
{
    int r;
    if (!port || !port->backend)
        return -EINVAL;
    account(port, &op);
    if (!port->backend->batching) {
        if (op.kind == EPP_OP_DATA_WRITE)
            op.buf = (uint8_t *)wdata;
        return port->backend->execute(port, &op, 1);
    }
    if (port->n_ops >= EPP_MAX_OPS)
        r = -ENOMEM;
    else
        r = grow((void **)&port->ops, &port->cap_ops, port->n_ops + 1, sizeof(struct epp_op),
                 EPP_INITIAL_OPS, EPP_MAX_OPS);
    if (!r && op.kind == EPP_OP_DATA_WRITE) {
        r = grow((void **)&port->pool, &port->cap_pool, port->n_pool + op.n, 1, EPP_INITIAL_POOL,
                 EPP_MAX_POOL);
        if (!r) {
            memcpy(port->pool + port->n_pool, wdata, op.n);
            op.val = (uint32_t)port->n_pool; /* offset; pointer fixed at flush */
            op.buf = NULL;
            port->n_pool += op.n;
        }
    }
    if (r) {
        epp_discard(port);
        return r;
    }
    port->ops[port->n_ops++] = op;
    return 0;
}

int epp_flush(epp_port_t *port)
{
    if (!port || !port->backend)
        return -EINVAL;
    if (!port->backend->batching || port->n_ops == 0)
        return 0;
    for (size_t i = 0; i < port->n_ops; i++)
        if (port->ops[i].kind == EPP_OP_DATA_WRITE)
            port->ops[i].buf = port->pool + port->ops[i].val;
    port->count.flushes++;
    int r = port->backend->execute(port, port->ops, port->n_ops);
    epp_discard(port);
    return r;
}

static uint8_t data_width(const epp_port_t *port, size_t n)
{
    if (!port->wide)
        return 1;
    if (n % 4 == 0)
        return 4;
    if (n % 2 == 0)
        return 2;
    return 1;
}

static int simple(epp_port_t *port, uint8_t kind, uint32_t val, uint8_t *out)
{
    struct epp_op op = {.kind = kind, .width = 1, .n = 1, .val = val, .buf = out};
    return push(port, op, NULL);
}

int epp_addr_write(epp_port_t *port, uint8_t addr)
{
    return simple(port, EPP_OP_ADDR_WRITE, addr, NULL);
}

int epp_addr_read(epp_port_t *port, uint8_t *out)
{
    if (!out)
        return -EINVAL;
    return simple(port, EPP_OP_ADDR_READ, 0, out);
}

static int data_op(epp_port_t *port, uint8_t kind, void *buf, size_t n, uint8_t width)
{
    if (!port || (!buf && n) || n > EPP_MAX_POOL)
        return -EINVAL;
    if (n == 0)
        return 0;
    struct epp_op op = {.kind = kind, .width = width, .n = (uint32_t)n, .val = 0,
                        .buf = kind == EPP_OP_DATA_READ ? buf : NULL};
    return push(port, op, buf);
}

int epp_data_write(epp_port_t *port, const void *buf, size_t n)
{
    return data_op(port, EPP_OP_DATA_WRITE, (void *)buf, n, port ? data_width(port, n) : 1);
}

int epp_data_write8(epp_port_t *port, const void *buf, size_t n)
{
    return data_op(port, EPP_OP_DATA_WRITE, (void *)buf, n, 1);
}

int epp_data_read(epp_port_t *port, void *buf, size_t n)
{
    return data_op(port, EPP_OP_DATA_READ, buf, n, port ? data_width(port, n) : 1);
}

int epp_status_read(epp_port_t *port, uint8_t *out)
{
    if (!out)
        return -EINVAL;
    return simple(port, EPP_OP_STATUS_READ, 0, out);
}

int epp_status_write(epp_port_t *port, uint8_t val)
{
    return simple(port, EPP_OP_STATUS_WRITE, val, NULL);
}

int epp_control_write(epp_port_t *port, uint8_t val)
{
    return simple(port, EPP_OP_CONTROL_WRITE, val, NULL);
}

int epp_spp_data_write(epp_port_t *port, uint8_t val)
{
    return simple(port, EPP_OP_SPP_DATA_WRITE, val, NULL);
}

int epp_ecr_write(epp_port_t *port, uint8_t val)
{
    return simple(port, EPP_OP_ECR_WRITE, val, NULL);
}

int epp_delay(epp_port_t *port, uint32_t ns)
{
    return simple(port, EPP_OP_DELAY, ns, NULL);
}

static int read_status_now(epp_port_t *port, uint8_t *st)
{
    int r = epp_status_read(port, st);
    if (!r)
        r = epp_flush(port);
    return r;
}

int epp_timeout(epp_port_t *port)
{
    uint8_t st = 0;
    int r = read_status_now(port, &st);
    if (r)
        return r;
    return (st & EPP_STATUS_TIMEOUT) ? 1 : 0;
}

int epp_clear_timeout_pluto(epp_port_t *port)
{
    uint8_t st = 0;
    int r = read_status_now(port, &st);
    if (!r)
        r = epp_status_write(port, (uint8_t)(st | 0x01u));
    if (!r)
        r = epp_status_write(port, (uint8_t)(st & 0xFEu));
    return r;
}

int epp_clear_timeout_hm2(epp_port_t *port)
{
    uint8_t st = 0, dummy = 0;
    int r = read_status_now(port, &st);
    if (r)
        return r;
    if (st & EPP_STATUS_TIMEOUT) {
        /* some chips need two reads before the write takes */
        if ((r = epp_status_read(port, &dummy)) || (r = read_status_now(port, &st)))
            return r;
        if ((r = epp_status_write(port, (uint8_t)(st | 0x01u))) ||
            (r = epp_status_write(port, (uint8_t)(st & 0xFEu))))
            return r;
    }
    r = epp_timeout(port);
    return r;
}

void epp_port_close(epp_port_t *port)
{
    if (!port)
        return;
    if (port->backend && port->backend->close)
        port->backend->close(port);
    free(port->ops);
    free(port->pool);
    port->ops = NULL;
    port->pool = NULL;
    port->n_ops = port->cap_ops = port->n_pool = port->cap_pool = 0;
    port->backend = NULL;
    port->priv = NULL;
}

/* ---- opening from the drivers' modparams ------------------------------- */

/* ioaddr < 16 is a Linux parport number, as LinuxCNC's uspace rtapi does:
 * its I/O addresses are in /proc/sys/dev/parport/parportN/base-addr. */
static int parport_base(long num, unsigned long *base, unsigned long *hi, char *err,
                        size_t errlen)
{
    char path[96];
    snprintf(path, sizeof(path), "/proc/sys/dev/parport/parport%ld/base-addr", num);
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "parport%ld: cannot read %s: %s (is parport_pc loaded?)", num,
                 path, strerror(errno));
        return -ENODEV;
    }
    unsigned long a = 0, b = 0;
    int n = fscanf(f, "%lu %lu", &a, &b);
    fclose(f);
    if (n < 1 || a == 0) {
        snprintf(err, errlen, "parport%ld: no I/O address in %s", num, path);
        return -ENODEV;
    }
    *base = a;
    *hi = n >= 2 ? b : 0;
    return 0;
}

/* "kind:ARG": the kind's backend opens it (epp_port_kinds). */
static int open_spec(epp_port_t *port, const char *spec, int wide, char *err, size_t errlen)
{
    for (size_t i = 0; i < epp_num_port_kinds; i++) {
        const struct epp_port_kind *k = epp_port_kinds[i];
        size_t n = strlen(k->prefix);
        if (strncmp(spec, k->prefix, n) == 0 && spec[n] == ':')
            return k->open(port, spec + n + 1, spec, wide, err, errlen);
    }
    char want[256] = "";
    size_t len = 0;
    for (size_t i = 0; i < epp_num_port_kinds && len < sizeof(want); i++) {
        const char *sep = i == 0 ? "" : i + 1 == epp_num_port_kinds ? " or " : ", ";
        len += (size_t)snprintf(want + len, sizeof(want) - len, "%s%s", sep,
                                epp_port_kinds[i]->usage);
    }
    snprintf(err, errlen, "port '%s': unknown port kind (want %s)", spec, want);
    return -EINVAL;
}

int epp_port_open(epp_port_t *port, const char *spec, long ioaddr, long ioaddr_hi, int wide,
                  char *err, size_t errlen)
{
    unsigned long base, hi;
    long hi_arg;
    int r;

    if (!port)
        return -EINVAL;
    if (spec && *spec)
        return open_spec(port, spec, wide, err, errlen);
    if (ioaddr < 0 || ioaddr > 0xFFFF) {
        snprintf(err, errlen, "ioaddr=%ld is not a parallel port address or number", ioaddr);
        return -EINVAL;
    }
    if (ioaddr < 16) {
        r = parport_base(ioaddr, &base, &hi, err, errlen);
        if (r)
            return r;
        if (ioaddr_hi == 0)
            ioaddr_hi = hi ? (long)hi : (long)base + 0x400;
    } else {
        base = (unsigned long)ioaddr;
        if (ioaddr_hi == 0)
            ioaddr_hi = ioaddr + 0x400;
    }
    hi_arg = ioaddr_hi < 0 ? -1 : ioaddr_hi;
    return epp_raw_open(port, &epp_raw_sys_io, base, hi_arg, wide, err, errlen);
}
