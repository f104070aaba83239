/* SPDX-License-Identifier: GPL-2.0-or-later */
/* jtag_gpio.c - bit-banged JTAG cable over a GPIO line layer
 * (hm2/jtag_gpio.h). */
#define _POSIX_C_SOURCE 200809L
#include "hm2/jtag_gpio.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

static const char *const role_names[JTAG_GPIO_N] = {"TCK", "TMS", "TDI", "TDO"};

static int line_fail(struct jtag_gpio *g, int r, const char *op, int role)
{
    snprintf(g->err, sizeof(g->err), "GPIO %s of line %s failed: %s", op, role_names[role],
             strerror(-r));
    return r;
}

static int gp_clock(void *ctx, const uint8_t *tms, const uint8_t *tdi, uint8_t *tdo, size_t n)
{
    struct jtag_gpio *g = ctx;
    const struct jtag_gpio_lines *l = &g->lines;
    for (size_t i = 0; i < n; i++) {
        int b_tms = (tms[i / 8] >> (i % 8)) & 1, b_tdi = (tdi[i / 8] >> (i % 8)) & 1, r;
        if ((r = l->set(l->ctx, JTAG_GPIO_TCK, 0)))
            return line_fail(g, r, "set", JTAG_GPIO_TCK);
        if ((r = l->set(l->ctx, JTAG_GPIO_TMS, b_tms)))
            return line_fail(g, r, "set", JTAG_GPIO_TMS);
        if ((r = l->set(l->ctx, JTAG_GPIO_TDI, b_tdi)))
            return line_fail(g, r, "set", JTAG_GPIO_TDI);
        if (tdo) {
            int v = 0;
            if ((r = l->get(l->ctx, JTAG_GPIO_TDO, &v)))
                return line_fail(g, r, "read", JTAG_GPIO_TDO);
            if (v)
                tdo[i / 8] |= (uint8_t)(1u << (i % 8));
            else
                tdo[i / 8] &= (uint8_t)~(1u << (i % 8));
        }
        if ((r = l->set(l->ctx, JTAG_GPIO_TCK, 1)))
            return line_fail(g, r, "set", JTAG_GPIO_TCK);
        g->tck++;
    }
    return 0;
}

static int gp_flush(void *ctx)
{
    (void)ctx;
    return 0; /* every bit is done when clock() returns */
}

static const char *gp_error(void *ctx)
{
    return ((struct jtag_gpio *)ctx)->err;
}

void jtag_gpio_init(struct jtag_gpio *g, const struct jtag_gpio_lines *lines)
{
    memset(g, 0, sizeof(*g));
    g->lines = *lines;
}

struct jtag_cable jtag_gpio_cable(struct jtag_gpio *g)
{
    return (struct jtag_cable){gp_clock, gp_flush, g, gp_error};
}
