/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pp_gpiod.c - a parallel-port connector wired to GPIO lines (a single-board
 * computer driving a breakout board): the port's registers are emulated on
 * the lines, with the same inversions a PC port has (status bit 7 = NOT pin
 * 11; control bits 0, 1, 3 = NOT pins 1, 14, 17), so hal_parport's register
 * code is the same for every backend.  Pins without a line read high (an
 * open TTL input) and outputs to them go nowhere.  Only lines whose level
 * changes are written.
 *
 * Line directions follow the mode: data lines are outputs (in: inputs),
 * control lines outputs (x: open-drain outputs, released high, read back
 * as inputs), status lines inputs.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pp_port.h"

static const int status_pin[5] = {15, 13, 12, 10, 11}; /* bits 3..7 */
static const int control_pin[4] = {1, 14, 16, 17};    /* bits 0..3 */
static const int control_inverted[4] = {1, 1, 0, 1};

struct gp_priv {
    struct pp_gpio_lines l;
    uint32_t out_level; /* level last set on each output pin (bit n = pin n) */
    uint32_t out_known; /* pins whose level is known */
    uint8_t data, control;
};

static int get_pin(struct gp_priv *g, int pin, int *level)
{
    if (!g->l.has(g->l.ctx, pin)) {
        *level = 1;
        return 0;
    }
    return g->l.get(g->l.ctx, pin, level);
}

static int set_pin(struct gp_priv *g, int pin, int level)
{
    uint32_t bit = 1u << pin;
    if (!g->l.has(g->l.ctx, pin))
        return 0;
    if ((g->out_known & bit) && !!(g->out_level & bit) == !!level)
        return 0;
    int r = g->l.set(g->l.ctx, pin, level);
    if (r) {
        g->out_known &= ~bit;
        return r;
    }
    g->out_known |= bit;
    g->out_level = level ? g->out_level | bit : g->out_level & ~bit;
    return 0;
}

static int gp_begin(struct pp_port *p)
{
    (void)p;
    return 0;
}

static int gp_read_data(struct pp_port *p, uint8_t *v)
{
    struct gp_priv *g = p->priv;
    if (p->mode != PP_MODE_IN) {
        *v = g->data;
        return 0;
    }
    uint8_t b = 0;
    for (int i = 0; i < 8; i++) {
        int lv, r = get_pin(g, i + 2, &lv);
        if (r)
            return r;
        b |= (uint8_t)((lv ? 1u : 0u) << i);
    }
    *v = b;
    return 0;
}

static int gp_write_data(struct pp_port *p, uint8_t v)
{
    struct gp_priv *g = p->priv;
    g->data = v;
    if (p->mode == PP_MODE_IN)
        return 0; /* drivers off: the latch only */
    for (int i = 0; i < 8; i++) {
        int r = set_pin(g, i + 2, (v >> i) & 1);
        if (r)
            return r;
    }
    return 0;
}

static int gp_read_status(struct pp_port *p, uint8_t *v)
{
    struct gp_priv *g = p->priv;
    uint8_t s = 0x06u;
    for (int i = 0; i < 5; i++) {
        int lv, r = get_pin(g, status_pin[i], &lv);
        if (r)
            return r;
        if (i == 4)
            lv = !lv; /* Busy is inverted */
        s |= (uint8_t)((lv ? 1u : 0u) << (3 + i));
    }
    *v = s;
    return 0;
}

static int gp_read_control(struct pp_port *p, uint8_t *v)
{
    struct gp_priv *g = p->priv;
    if (p->mode != PP_MODE_X) {
        *v = g->control;
        return 0;
    }
    uint8_t c = (uint8_t)(g->control & 0x30u);
    for (int i = 0; i < 4; i++) {
        int lv, r = get_pin(g, control_pin[i], &lv);
        if (r)
            return r;
        if (control_inverted[i])
            lv = !lv;
        c |= (uint8_t)((lv ? 1u : 0u) << i);
    }
    *v = c;
    return 0;
}

static int gp_write_control(struct pp_port *p, uint8_t v)
{
    struct gp_priv *g = p->priv;
    g->control = (uint8_t)(v & 0x3fu);
    for (int i = 0; i < 4; i++) {
        int bit = (v >> i) & 1;
        int r = set_pin(g, control_pin[i], control_inverted[i] ? !bit : bit);
        if (r)
            return r;
    }
    return 0;
}

static void gp_close(struct pp_port *p)
{
    struct gp_priv *g = p->priv;
    if (!g)
        return;
    if (g->l.close)
        g->l.close(g->l.ctx);
    free(g);
    p->priv = NULL;
}

static const struct pp_ops gpiod_ops = {gp_begin,        gp_read_data,    gp_write_data,
                                        gp_read_status,  gp_read_control, gp_write_control,
                                        gp_close};

/* Request every wired line for the mode. */
static int configure(struct gp_priv *g, enum pp_mode mode, char *err, size_t errlen,
                     const char *name)
{
    for (int pin = 1; pin <= 17; pin++) {
        if (!g->l.has(g->l.ctx, pin))
            continue;
        int is_data = pin >= 2 && pin <= 9, is_status = pin >= 10 && pin <= 15 && pin != 14;
        int out = 1, od = 0, level = 0;
        if (is_status || (is_data && mode == PP_MODE_IN))
            out = 0;
        else if (!is_data) { /* control pins start released / high */
            level = 1;
            od = mode == PP_MODE_X;
        }
        int r = g->l.config(g->l.ctx, pin, out, od, level);
        if (r) {
            snprintf(err, errlen, "gpiod port %s: cannot request the line of pin %d as %s: %s",
                     name, pin, !out ? "input" : od ? "open-drain output" : "output",
                     strerror(-r));
            return r;
        }
        if (out) {
            g->out_known |= 1u << pin;
            g->out_level |= (uint32_t)level << pin;
        }
    }
    return 0;
}

int pp_gpiod_open(struct pp_port *p, const struct pp_gpio_lines *l, const char *name,
                  enum pp_mode mode, char *err, size_t errlen)
{
    struct gp_priv *g = calloc(1, sizeof(*g));
    if (!g) {
        snprintf(err, errlen, "gpiod port %s: out of memory", name);
        if (l->close)
            l->close(l->ctx);
        return -ENOMEM;
    }
    g->l = *l;
    /* the power-on register values of a PC port: all control pins high */
    g->control = (uint8_t)(0x04u | (mode == PP_MODE_IN ? PP_CTRL_DIR : 0u));
    snprintf(p->name, sizeof(p->name), "gpiod %s", name);
    p->kind = "gpiod";
    p->ops = &gpiod_ops;
    p->priv = g;
    p->mode = mode;
    int r = configure(g, mode, err, errlen, name);
    if (r) {
        gp_close(p);
        return r;
    }
    return 0;
}
