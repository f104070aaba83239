/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * epp_gpiod.c - EPP bit-banged on GPIO lines (a single-board computer wired
 * to a Pluto-P or 7i43 EPP connector).  The EPP handshake (IEEE 1284):
 *
 *   1. wait until nWait is low (peripheral ready)
 *   2. nWrite low + drive the bus (write) or nWrite high + release it (read)
 *   3. strobe low (nAddrStr for address cycles, nDataStr for data cycles)
 *   4. wait until nWait is high (acknowledge); sample the bus on reads
 *   5. strobe high, wait until nWait is low again, nWrite high
 *
 * A step that waits longer than the timeout (a PC port: ~10 us) aborts the
 * cycle (strobe released) and sets the timeout bit; like a PC port, no
 * further cycles run until a status write clears it.  The SPP registers map
 * onto the same lines (control bit 0 -> nStrobe = nWrite line, bit 1 ->
 * nAutoFd = nDataStr, bit 3 -> nSelectIn = nAddrStr, all inverted; bit 2 ->
 * nInit, not inverted), so the Pluto's FPGA upload works too when the
 * optional nInit line is wired.  The line layer is a table so the unit
 * tests run this code against a simulated peripheral.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/epp_port.h"

void epp_backend_delay(uint32_t ns);

struct gpiod_priv {
    struct epp_gpio_lines l;
    uint32_t timeout_ns;
    int timeout;    /* sticky EPP timeout bit */
    int driving;    /* data bus direction as last set, -1 unknown */
};

static int bus_dir(struct gpiod_priv *p, int out)
{
    if (p->driving == out)
        return 0;
    int r = p->l.data_dir(p->l.ctx, out);
    if (!r)
        p->driving = out;
    return r;
}

/* Wait for nWait == level.  1 on timeout, 0 when seen, -errno. */
static int wait_nwait(struct gpiod_priv *p, int level)
{
    uint64_t start = p->l.now_ns(p->l.ctx);
    for (;;) {
        int v = 0;
        int r = p->l.get(p->l.ctx, EPP_GPIO_NWAIT, &v);
        if (r)
            return r;
        if (v == level)
            return 0;
        if (p->l.now_ns(p->l.ctx) - start > p->timeout_ns)
            return 1;
    }
}

/* One EPP cycle.  strobe: EPP_GPIO_NADDRSTR or EPP_GPIO_NDATASTR. */
static int cycle(struct gpiod_priv *p, int strobe, int is_read, uint8_t *byte)
{
    int r, t;
    if (p->timeout) {
        if (is_read)
            *byte = 0xFF;
        return 0;
    }
    if ((t = wait_nwait(p, 0)) != 0)
        goto timeout;
    if (is_read) {
        if ((r = p->l.set(p->l.ctx, EPP_GPIO_NWRITE, 1)) || (r = bus_dir(p, 0)))
            return r;
    } else {
        if ((r = bus_dir(p, 1)) || (r = p->l.data_set(p->l.ctx, *byte)) ||
            (r = p->l.set(p->l.ctx, EPP_GPIO_NWRITE, 0)))
            return r;
    }
    if ((r = p->l.set(p->l.ctx, strobe, 0)))
        return r;
    t = wait_nwait(p, 1);
    if (t == 0 && is_read)
        t = p->l.data_get(p->l.ctx, byte) ? -EIO : 0;
    if ((r = p->l.set(p->l.ctx, strobe, 1)))
        return r;
    if (t == 0)
        t = wait_nwait(p, 0);
    if ((r = p->l.set(p->l.ctx, EPP_GPIO_NWRITE, 1)))
        return r;
    if (t == 0)
        return 0;
timeout:
    if (t < 0)
        return t;
    if (is_read)
        *byte = 0xFF;
    p->timeout = 1;
    return 0;
}

static int gpiod_execute(epp_port_t *port, const struct epp_op *ops, size_t n)
{
    struct gpiod_priv *p = port->priv;
    int r = 0;
    for (size_t i = 0; i < n && !r; i++) {
        const struct epp_op *op = &ops[i];
        uint8_t v;
        int lv;
        switch (op->kind) {
        case EPP_OP_ADDR_WRITE:
            v = (uint8_t)op->val;
            r = cycle(p, EPP_GPIO_NADDRSTR, 0, &v);
            break;
        case EPP_OP_ADDR_READ:
            r = cycle(p, EPP_GPIO_NADDRSTR, 1, op->buf);
            break;
        case EPP_OP_DATA_WRITE:
            for (uint32_t k = 0; k < op->n && !r; k++) {
                v = op->buf[k];
                r = cycle(p, EPP_GPIO_NDATASTR, 0, &v);
            }
            break;
        case EPP_OP_DATA_READ:
            for (uint32_t k = 0; k < op->n && !r; k++)
                r = cycle(p, EPP_GPIO_NDATASTR, 1, &op->buf[k]);
            break;
        case EPP_OP_STATUS_READ:
            /* bit 7 = Busy inverted (nWait pin high -> 0), bit 0 timeout */
            lv = 0;
            r = p->l.get(p->l.ctx, EPP_GPIO_NWAIT, &lv);
            if (!r)
                op->buf[0] = (uint8_t)((lv ? 0x00 : 0x80) | (p->timeout ? 1 : 0));
            break;
        case EPP_OP_STATUS_WRITE:
            p->timeout = 0;
            break;
        case EPP_OP_CONTROL_WRITE:
            v = (uint8_t)op->val;
            r = p->l.set(p->l.ctx, EPP_GPIO_NWRITE, !(v & 0x01));
            if (!r)
                r = p->l.set(p->l.ctx, EPP_GPIO_NDATASTR, !(v & 0x02));
            if (!r)
                r = p->l.set(p->l.ctx, EPP_GPIO_NADDRSTR, !(v & 0x08));
            if (!r && p->l.has_ninit)
                r = p->l.set(p->l.ctx, EPP_GPIO_NINIT, (v & 0x04) ? 1 : 0);
            break;
        case EPP_OP_SPP_DATA_WRITE:
            r = bus_dir(p, 1);
            if (!r)
                r = p->l.data_set(p->l.ctx, (uint8_t)op->val);
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

static void gpiod_close(epp_port_t *port)
{
    struct gpiod_priv *p = port->priv;
    if (!p)
        return;
    if (p->l.close)
        p->l.close(p->l.ctx);
    free(p);
}

static const struct epp_backend gpiod_backend = {"gpiod", 0, gpiod_execute, gpiod_close};

int epp_gpiod_open(epp_port_t *port, const struct epp_gpio_lines *lines, uint32_t timeout_ns,
                   const char *name, char *err, size_t errlen)
{
    if (!lines || !lines->data_dir || !lines->data_set || !lines->data_get || !lines->set ||
        !lines->get || !lines->now_ns || timeout_ns == 0) {
        snprintf(err, errlen, "gpiod port %s: incomplete line layer", name ? name : "?");
        return -EINVAL;
    }
    struct gpiod_priv *p = calloc(1, sizeof(*p));
    if (!p) {
        snprintf(err, errlen, "gpiod port %s: out of memory", name ? name : "?");
        return -ENOMEM;
    }
    p->l = *lines;
    p->timeout_ns = timeout_ns;
    p->driving = -1;
    /* Idle bus: strobes and nWrite high, bus released. */
    int r = p->l.set(p->l.ctx, EPP_GPIO_NWRITE, 1);
    if (!r)
        r = p->l.set(p->l.ctx, EPP_GPIO_NDATASTR, 1);
    if (!r)
        r = p->l.set(p->l.ctx, EPP_GPIO_NADDRSTR, 1);
    if (!r && p->l.has_ninit)
        r = p->l.set(p->l.ctx, EPP_GPIO_NINIT, 1);
    if (!r)
        r = bus_dir(p, 0);
    if (r) {
        snprintf(err, errlen, "gpiod port %s: cannot set the idle line levels: %s",
                 name ? name : "?", strerror(-r));
        free(p);
        return r;
    }
    epp_port_init(port, &gpiod_backend, p, name, 0);
    return 0;
}

/* ---- the gpiod:CHIP:LINES[:OPTS] port kind ---- */

static int gpiod_open_spec(epp_port_t *port, const char *arg, const char *spec, int wide,
                           char *err, size_t errlen)
{
    (void)wide; /* bit-banged: one byte per cycle */
    struct epp_gpio_lines lines;
    uint32_t timeout_ns = 10000;
    int r = epp_gpiod_lines_open(&lines, arg, &timeout_ns, err, errlen);
    if (r)
        return r;
    r = epp_gpiod_open(port, &lines, timeout_ns, spec, err, errlen);
    if (r)
        lines.close(lines.ctx);
    return r;
}

const struct epp_port_kind epp_gpiod_kind = {"gpiod", "gpiod:CHIP:LINES", gpiod_open_spec};
