/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pp_sim.c - the virtual parallel port (vparport, sim/parport) behind the
 * raw backend: the port instructions (ioperm, inb, outb) act on the virtual
 * port's registers instead of the I/O bus, so everything above them is the
 * code that drives a real port.  The port sits at the usual 0x378 with its
 * ECR (when created with one) at 0x778; accesses without a prior ioperm of
 * the address are counted as errors (on real hardware they would fault).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pp_port.h"
#include "vpp.h"

#define SIM_BASE 0x378ul

struct sim_priv {
    struct vpp_state *st;
    struct pp_port *port;
    struct pp_ops ops; /* the raw backend's, with our close */
    void (*raw_close)(struct pp_port *p);
    int pid;
    unsigned long unpermitted; /* accesses to addresses never granted */
    uint8_t perm[0x10000 / 8];
};

static uint64_t stamp(struct sim_priv *s)
{
    long long t = s->port && s->port->clock ? s->port->clock() : 0;
    if (s->port && t < s->port->stamp_floor)
        t = s->port->stamp_floor;
    return t < 0 ? 0u : (uint64_t)t;
}

static int permitted(struct sim_priv *s, unsigned long a)
{
    if (a < 0x10000 && (s->perm[a / 8] >> (a % 8)) & 1u)
        return 1;
    s->unpermitted++;
    return 0;
}

static int sim_ioperm(void *ctx, unsigned long from, unsigned long num, int on)
{
    struct sim_priv *s = ctx;
    if (from + num > 0x10000)
        return -EINVAL;
    for (unsigned long a = from; a < from + num; a++) {
        if (on)
            s->perm[a / 8] |= (uint8_t)(1u << (a % 8));
        else
            s->perm[a / 8] &= (uint8_t)~(1u << (a % 8));
    }
    return 0;
}

static uint8_t sim_inb(void *ctx, unsigned long port)
{
    struct sim_priv *s = ctx;
    if (!permitted(s, port) || port < SIM_BASE)
        return 0xffu;
    return vpp_inb(s->st, (unsigned)(port - SIM_BASE), stamp(s));
}

static void sim_outb(void *ctx, uint8_t v, unsigned long port)
{
    struct sim_priv *s = ctx;
    if (!permitted(s, port) || port < SIM_BASE)
        return;
    vpp_outb(s->st, (unsigned)(port - SIM_BASE), v, stamp(s));
}

static void sim_close(struct pp_port *p)
{
    struct sim_priv *s = NULL;
    /* the raw backend's priv is not ours: find ours through the ops */
    s = (struct sim_priv *)((char *)p->ops - offsetof(struct sim_priv, ops));
    s->raw_close(p);
    vpp_release(s->st, s->pid);
    vpp_close(s->st);
    free(s);
}

/* For the unit tests: accesses the driver made without permission. */
unsigned long pp_sim_unpermitted(const struct pp_port *p);
unsigned long pp_sim_unpermitted(const struct pp_port *p)
{
    const struct sim_priv *s =
        (const struct sim_priv *)((const char *)p->ops - offsetof(struct sim_priv, ops));
    return s->unpermitted;
}

int pp_sim_open(struct pp_port *p, const char *vname, long hi, enum pp_mode mode, char *err,
                size_t errlen)
{
    char why[600];
    struct sim_priv *s = calloc(1, sizeof(*s));
    if (!s) {
        snprintf(err, errlen, "sim:%s: out of memory", vname);
        return -ENOMEM;
    }
    s->pid = (int)getpid();
    s->port = p;
    int r = vpp_open(vname, &s->st, why, sizeof(why));
    if (r) {
        snprintf(err, errlen, "sim:%s: %s", vname, why);
        free(s);
        return r;
    }
    r = vpp_claim(s->st, s->pid, vname, why, sizeof(why));
    if (r) {
        snprintf(err, errlen, "sim:%s: %s", vname, why);
        vpp_close(s->st);
        free(s);
        return r;
    }
    const struct epp_raw_io io = {sim_ioperm, sim_inb, NULL, NULL, sim_outb, NULL, NULL, s};
    r = pp_raw_open(p, &io, NULL, SIM_BASE, hi, -1, mode, err, errlen);
    if (r) {
        vpp_release(s->st, s->pid);
        vpp_close(s->st);
        free(s);
        return r;
    }
    s->ops = *p->ops;
    s->raw_close = s->ops.close;
    s->ops.close = sim_close;
    p->ops = &s->ops;
    p->kind = "sim";
    snprintf(p->name, sizeof(p->name), "sim:%s", vname);
    return 0;
}
