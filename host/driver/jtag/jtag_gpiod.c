/* SPDX-License-Identifier: GPL-2.0-or-later */
/* jtag_gpiod.c - libgpiod (1.6 API) lines for the bit-banged JTAG cable
 * (hm2/jtag_gpio.h), with the line-spec parser the gpiod EPP port uses. */
#define _GNU_SOURCE
#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/gpiod_linespec.h"
#include "hm2/jtag_gpio.h"

#define CONSUMER "hm2flash-jtag"

struct gpiod_jtag {
    struct gpiod_chip *chip;
    struct gpiod_line *line[JTAG_GPIO_N];
};

static int gj_set(void *ctx, int role, int level)
{
    struct gpiod_jtag *p = ctx;
    return gpiod_line_set_value(p->line[role], level ? 1 : 0) ? -errno : 0;
}

static int gj_get(void *ctx, int role, int *level)
{
    struct gpiod_jtag *p = ctx;
    int v = gpiod_line_get_value(p->line[role]);
    if (v < 0)
        return -errno;
    *level = v;
    return 0;
}

static void gj_close(void *ctx)
{
    struct gpiod_jtag *p = ctx;
    if (!p)
        return;
    for (int i = 0; i < JTAG_GPIO_N; i++)
        if (p->line[i] && gpiod_line_is_requested(p->line[i]))
            gpiod_line_release(p->line[i]);
    if (p->chip)
        gpiod_chip_close(p->chip);
    free(p);
}

int jtag_gpiod_lines_open(struct jtag_gpio_lines *lines, const char *spec, char *err,
                          size_t errlen)
{
    static const char *const roles[JTAG_GPIO_N] = {"TCK", "TMS", "TDI", "TDO"};
    struct gpiod_linespec ls;
    int r = gpiod_linespec_parse(spec, "JTAG gpiod cable", roles, JTAG_GPIO_N, 0, NULL, 0, &ls,
                                 err, errlen);
    if (r)
        return r;
    if (ls.n != JTAG_GPIO_N) {
        snprintf(err, errlen, "JTAG gpiod cable '%s': want 4 lines TCK/TMS/TDI/TDO, got %d",
                 spec, ls.n);
        return -EINVAL;
    }
    struct gpiod_jtag *p = calloc(1, sizeof(*p));
    if (!p) {
        snprintf(err, errlen, "out of memory");
        return -ENOMEM;
    }
    p->chip = gpiod_chip_open_lookup(ls.chip);
    if (!p->chip) {
        r = -errno;
        snprintf(err, errlen, "JTAG gpiod cable: cannot open GPIO chip '%s': %s", ls.chip,
                 strerror(errno));
        goto fail;
    }
    for (int i = 0; i < JTAG_GPIO_N; i++) {
        p->line[i] = gpiod_chip_get_line(p->chip, (unsigned)ls.offset[i]);
        int e = !p->line[i] ? -1
                : i == JTAG_GPIO_TDO ? gpiod_line_request_input(p->line[i], CONSUMER)
                                     : gpiod_line_request_output(p->line[i], CONSUMER,
                                                                 i == JTAG_GPIO_TMS);
        if (e) {
            r = -errno;
            snprintf(err, errlen, "JTAG gpiod cable: cannot get line %d (%s) of %s: %s",
                     ls.offset[i], roles[i], ls.chip, strerror(errno));
            goto fail;
        }
    }
    *lines = (struct jtag_gpio_lines){gj_set, gj_get, gj_close, p};
    return 0;
fail:
    gj_close(p);
    return r ? r : -EIO;
}
