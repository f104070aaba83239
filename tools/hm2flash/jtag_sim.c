/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * jtag_sim.c - the four JTAG lines of a virtual board (vboard's VB_JTAG
 * request: the levels of TCK, TMS, TDI in, TDO out), for the GPIO cable
 * engine: hm2flash --jtag sim:SOCKET.  The engine's line sequence is the
 * one it gives libgpiod; only the wire is simulated.
 */
#define _GNU_SOURCE
#include "jtag_sim.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vboard_client.h"

struct sim_lines {
    vbc_t c;
    uint32_t levels; /* bit 0 TCK, 1 TMS, 2 TDI */
    uint32_t tdo;
};

static int send_levels(struct sim_lines *s)
{
    int r = vbc_call(&s->c, VB_JTAG, 0, &s->levels, sizeof(s->levels));
    if (r)
        return r;
    if (s->c.rx_len != 4)
        return -EPROTO;
    memcpy(&s->tdo, s->c.rx, 4);
    return 0;
}

static int sim_set(void *ctx, int role, int level)
{
    struct sim_lines *s = ctx;
    static const uint32_t bit[] = {1u, 2u, 4u};
    if (role < JTAG_GPIO_TCK || role > JTAG_GPIO_TDI)
        return -EINVAL;
    s->levels = level ? s->levels | bit[role] : s->levels & ~bit[role];
    return send_levels(s);
}

static int sim_get(void *ctx, int role, int *level)
{
    struct sim_lines *s = ctx;
    if (role != JTAG_GPIO_TDO)
        return -EINVAL;
    *level = (int)(s->tdo & 1u); /* TDO as of the last line change */
    return 0;
}

static void sim_close(void *ctx)
{
    struct sim_lines *s = ctx;
    vbc_close(&s->c);
    free(s);
}

int jtag_sim_lines_open(struct jtag_gpio_lines *lines, const char *path, char *err,
                        size_t errlen)
{
    struct sim_lines *s = calloc(1, sizeof(*s));
    if (!s) {
        snprintf(err, errlen, "out of memory");
        return -ENOMEM;
    }
    s->c.fd = -1;
    int r = vbc_open(&s->c, path);
    if (!r)
        r = send_levels(s); /* all low; also: does the board have a JTAG port? */
    if (r) {
        if (s->c.err[0])
            snprintf(err, errlen, "%s", s->c.err);
        else
            snprintf(err, errlen, "virtual board at %s: %s", path, strerror(-r));
        vbc_close(&s->c);
        free(s);
        return r;
    }
    lines->set = sim_set;
    lines->get = sim_get;
    lines->close = sim_close;
    lines->ctx = s;
    return 0;
}
