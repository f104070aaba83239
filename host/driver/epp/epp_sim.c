/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * epp_sim.c - the sim: backend of epp_port: the virtual board
 * (bin/vboard --board pluto, docs/vboard.md).  Batching: a flush sends every
 * queued operation as one VB_EPP request (sim/verilator/include/vboard/
 * proto.h) and fills the read buffers from the reply, so a servo period
 * costs one round trip per flush.  Each request carries rtapi_get_time():
 * under HAL's simulated clock the board runs in lockstep with the threads.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/epp_port.h"
#include "vboard_client.h"

/* Weak: a program without libhal (a unit test, a tool) sends time 0, which
 * the board takes as "do not advance". */
extern long long rtapi_get_time(void) __attribute__((weak));
extern int rtapi_is_simclock(void) __attribute__((weak));

struct epp_sim {
    vbc_t c;
    int reported; /* the transport failure was printed */
};

static uint64_t host_time(void)
{
    return rtapi_get_time ? (uint64_t)rtapi_get_time() : 0;
}

static size_t reply_bytes(const struct epp_op *op)
{
    switch (op->kind) {
    case EPP_OP_ADDR_READ:
    case EPP_OP_STATUS_READ:
        return 1;
    case EPP_OP_DATA_READ:
        return op->n;
    default:
        return 0;
    }
}

static int build(struct epp_sim *s, const struct epp_op *ops, size_t n, size_t *expect)
{
    vbc_req_start(&s->c);
    *expect = 0;
    for (size_t i = 0; i < n; i++) {
        struct vb_epp_op w = {.kind = ops[i].kind, .n = ops[i].n, .val = ops[i].val};
        int r = vbc_req_put(&s->c, &w, sizeof w);
        if (!r && ops[i].kind == EPP_OP_DATA_WRITE && ops[i].n)
            r = vbc_req_put(&s->c, ops[i].buf, ops[i].n);
        if (r)
            return r;
        *expect += reply_bytes(&ops[i]);
    }
    return 0;
}

static int sim_execute(epp_port_t *port, const struct epp_op *ops, size_t n)
{
    struct epp_sim *s = port->priv;
    size_t expect, off = 0;
    int r = build(s, ops, n, &expect);
    if (!r)
        r = vbc_send(&s->c, VB_EPP, host_time());
    if (!r && s->c.rx_len != expect) {
        snprintf(s->c.err, sizeof s->c.err,
                 "virtual board %s: EPP reply has %zu bytes, the %zu operations read %zu",
                 s->c.path, s->c.rx_len, n, expect);
        r = -EPROTO;
    }
    if (r) {
        if (!s->reported)
            fprintf(stderr, "%s: EPP request failed: %s\n", port->name, s->c.err);
        s->reported = 1;
        return r == -ENOMEM ? r : -EIO;
    }
    s->reported = 0;
    for (size_t i = 0; i < n; i++) {
        size_t k = reply_bytes(&ops[i]);
        if (k)
            memcpy(ops[i].buf, s->c.rx + off, k);
        off += k;
    }
    return 0;
}

static void sim_close(epp_port_t *port)
{
    struct epp_sim *s = port->priv;
    if (!s)
        return;
    vbc_close(&s->c);
    if (s->reported && vbc_remove_stale(s->c.path))
        fprintf(stderr, "%s: removed the socket left by the dead board\n", port->name);
    free(s);
    port->priv = NULL;
}

static const struct epp_backend sim_backend = {
    .kind = "sim", .batching = 1, .execute = sim_execute, .close = sim_close};

int epp_sim_open(epp_port_t *port, const char *socket_path, int wide, char *err, size_t errlen)
{
    struct vb_hello h;
    struct epp_sim *s = calloc(1, sizeof *s);
    int r;
    if (!s) {
        snprintf(err, errlen, "sim:%s: out of memory", socket_path);
        return -ENOMEM;
    }
    if ((r = vbc_open(&s->c, socket_path)) < 0)
        goto fail;
    if ((r = vbc_hello(&s->c, &h)) < 0)
        goto fail;
    if (h.bus != VB_BUS_EPP_PLUTO && h.bus != VB_BUS_EPP_HM2) {
        snprintf(s->c.err, sizeof s->c.err,
                 "virtual board %s is a %.16s on a local bus, not an EPP board", socket_path,
                 h.board);
        r = -ENODEV;
        goto fail;
    }
    /* in a HAL session the requests carry its time: a lockstep board needs
     * the simulated clock */
    if (rtapi_get_time && rtapi_is_simclock &&
        (r = vbc_check_clock(&s->c, &h, rtapi_is_simclock())) < 0)
        goto fail;
    char name[64];
    snprintf(name, sizeof name, "sim:%s", socket_path);
    epp_port_init(port, &sim_backend, s, name, wide);
    return 0;
fail:
    snprintf(err, errlen, "%s", s->c.err);
    vbc_close(&s->c);
    free(s);
    return r;
}

/* ---- the sim:SOCKET port kind ---- */

static int sim_open_spec(epp_port_t *port, const char *arg, const char *spec, int wide,
                         char *err, size_t errlen)
{
    if (!*arg) {
        snprintf(err, errlen, "port '%s': missing socket path (sim:/tmp/vb.sock)", spec);
        return -EINVAL;
    }
    return epp_sim_open(port, arg, wide, err, errlen);
}

const struct epp_port_kind epp_sim_kind = {"sim", "sim:SOCKET", sim_open_spec};
