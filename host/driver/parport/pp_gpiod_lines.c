/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pp_gpiod_lines.c - the real line layer of hal_parport's gpiod backend,
 * written against libgpiod 1.6: one chip, one line per DB-25 pin 1..17.
 *
 * Spec (the part after "gpiod:", parsed by gpiod_linespec):
 *     CHIP:lines=P1/P2/.../P17      '-' for a pin with no line
 */
#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/gpiod_linespec.h"
#include "pp_port.h"

#define CONSUMER "hal_parport"

static const char *const pin_role[17] = {"pin 1",  "pin 2",  "pin 3",  "pin 4",  "pin 5",
                                         "pin 6",  "pin 7",  "pin 8",  "pin 9",  "pin 10",
                                         "pin 11", "pin 12", "pin 13", "pin 14", "pin 15",
                                         "pin 16", "pin 17"};

struct lines_priv {
    struct gpiod_chip *chip;
    int offset[18];                /* by pin, GPIOD_LINESPEC_NC = none */
    struct gpiod_line *line[18];   /* requested lines */
};

static int l_has(void *ctx, int pin)
{
    struct lines_priv *lp = ctx;
    return pin >= 1 && pin <= 17 && lp->offset[pin] != GPIOD_LINESPEC_NC;
}

static int l_config(void *ctx, int pin, int out, int od, int level)
{
    struct lines_priv *lp = ctx;
    if (!l_has(ctx, pin))
        return -EINVAL;
    struct gpiod_line *line = gpiod_chip_get_line(lp->chip, (unsigned)lp->offset[pin]);
    if (!line)
        return errno ? -errno : -EINVAL;
    int r = out ? gpiod_line_request_output_flags(line, CONSUMER,
                                                  od ? GPIOD_LINE_REQUEST_FLAG_OPEN_DRAIN : 0,
                                                  level)
                : gpiod_line_request_input(line, CONSUMER);
    if (r)
        return errno ? -errno : -EBUSY;
    lp->line[pin] = line;
    return 0;
}

static int l_set(void *ctx, int pin, int level)
{
    struct lines_priv *lp = ctx;
    if (!l_has(ctx, pin) || !lp->line[pin])
        return -EINVAL;
    return gpiod_line_set_value(lp->line[pin], level ? 1 : 0) ? -errno : 0;
}

static int l_get(void *ctx, int pin, int *level)
{
    struct lines_priv *lp = ctx;
    if (!l_has(ctx, pin) || !lp->line[pin])
        return -EINVAL;
    int v = gpiod_line_get_value(lp->line[pin]);
    if (v < 0)
        return -errno;
    *level = v;
    return 0;
}

static void l_close(void *ctx)
{
    struct lines_priv *lp = ctx;
    if (!lp)
        return;
    for (int pin = 1; pin <= 17; pin++)
        if (lp->line[pin])
            gpiod_line_release(lp->line[pin]);
    if (lp->chip)
        gpiod_chip_close(lp->chip);
    free(lp);
}

/* Parse only (for the unit tests): 17 roles, '-' allowed. */
int pp_gpiod_parse(const char *spec, struct gpiod_linespec *ls, char *err, size_t errlen);
int pp_gpiod_parse(const char *spec, struct gpiod_linespec *ls, char *err, size_t errlen)
{
    int r = gpiod_linespec_parse(spec, "gpiod port", pin_role, 17, 1, NULL, 0, ls, err, errlen);
    if (r)
        return r;
    if (ls->n != 17) {
        snprintf(err, errlen,
                 "gpiod port '%s': need 17 line offsets, one per pin 1..17 ('-' for a pin "
                 "that is not wired), got %d",
                 spec, ls->n);
        return -EINVAL;
    }
    return 0;
}

int pp_gpiod_lines_open(struct pp_gpio_lines *l, const char *spec, char *err, size_t errlen)
{
    struct gpiod_linespec ls;
    int r = pp_gpiod_parse(spec, &ls, err, errlen);
    if (r)
        return r;
    struct lines_priv *lp = calloc(1, sizeof(*lp));
    if (!lp) {
        snprintf(err, errlen, "gpiod port '%s': out of memory", spec);
        return -ENOMEM;
    }
    lp->offset[0] = GPIOD_LINESPEC_NC;
    for (int i = 0; i < 17; i++)
        lp->offset[i + 1] = ls.offset[i];
    lp->chip = gpiod_chip_open_lookup(ls.chip);
    if (!lp->chip) {
        r = errno ? -errno : -ENODEV;
        snprintf(err, errlen, "gpiod port '%s': cannot open GPIO chip '%s': %s", spec, ls.chip,
                 strerror(-r));
        free(lp);
        return r;
    }
    memset(l, 0, sizeof(*l));
    l->config = l_config;
    l->set = l_set;
    l->get = l_get;
    l->has = l_has;
    l->close = l_close;
    l->ctx = lp;
    return 0;
}
