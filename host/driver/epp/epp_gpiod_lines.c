/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _GNU_SOURCE
/*
 * epp_gpiod_lines.c - the real GPIO line layer of the gpiod EPP backend,
 * written against libgpiod 1.6 (Debian's libgpiod-dev): one chip, 12 lines
 * (D0-D7, nWrite, nDataStr, nAddrStr, nWait) plus an optional 13th (nInit).
 *
 * Spec (the part after "gpiod:", parsed by gpiod_linespec):
 *     CHIP:lines=D0/D1/.../D7/NWRITE/NDATASTR/NADDRSTR/NWAIT[/NINIT][:timeout_us=N]
 * CHIP is anything gpiod_chip_open_lookup() accepts (gpiochip0,
 * /dev/gpiochip0, a label or a number); line offsets are separated by '/'
 * or ',' ('/' inside comma-separated array modparams).  "lines=" may be
 * left out.  See docs/epp_port.md.
 */
#include <errno.h>
#include <gpiod.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hm2/epp_port.h"
#include "hm2/gpiod_linespec.h"

struct lines_priv {
    struct gpiod_chip *chip;
    struct gpiod_line *line[EPP_GPIO_NLINES];
    struct gpiod_line_bulk data;
    int nlines;
};

static const char *const role_name[EPP_GPIO_NLINES] = {
    "D0", "D1", "D2", "D3", "D4", "D5", "D6", "D7", "nWrite", "nDataStr", "nAddrStr", "nWait",
    "nInit"};

#define CONSUMER "hm2-epp"

static int l_data_dir(void *ctx, int out)
{
    struct lines_priv *p = ctx;
    int r;
    if (out) {
        int zeros[8] = {0};
        r = gpiod_line_set_direction_output_bulk(&p->data, zeros);
    } else {
        r = gpiod_line_set_direction_input_bulk(&p->data);
    }
    return r ? -errno : 0;
}

static int l_data_set(void *ctx, uint8_t v)
{
    struct lines_priv *p = ctx;
    int vals[8];
    for (int i = 0; i < 8; i++)
        vals[i] = (v >> i) & 1;
    return gpiod_line_set_value_bulk(&p->data, vals) ? -errno : 0;
}

static int l_data_get(void *ctx, uint8_t *v)
{
    struct lines_priv *p = ctx;
    int vals[8];
    if (gpiod_line_get_value_bulk(&p->data, vals))
        return -errno;
    uint8_t b = 0;
    for (int i = 0; i < 8; i++)
        b |= (uint8_t)((vals[i] ? 1 : 0) << i);
    *v = b;
    return 0;
}

static int l_set(void *ctx, int role, int level)
{
    struct lines_priv *p = ctx;
    if (role < 0 || role >= p->nlines || role == EPP_GPIO_NWAIT)
        return -EINVAL;
    return gpiod_line_set_value(p->line[role], level ? 1 : 0) ? -errno : 0;
}

static int l_get(void *ctx, int role, int *level)
{
    struct lines_priv *p = ctx;
    if (role < 0 || role >= p->nlines)
        return -EINVAL;
    int v = gpiod_line_get_value(p->line[role]);
    if (v < 0)
        return -errno;
    *level = v;
    return 0;
}

static uint64_t l_now(void *ctx)
{
    (void)ctx;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void l_close(void *ctx)
{
    struct lines_priv *p = ctx;
    if (!p)
        return;
    for (int i = 0; i < p->nlines; i++)
        if (p->line[i] && gpiod_line_is_requested(p->line[i]))
            gpiod_line_release(p->line[i]);
    if (p->chip)
        gpiod_chip_close(p->chip);
    free(p);
}

/* Parse the spec into chip name, offsets and options (no system access;
 * exposed for the unit tests).  The syntax is gpiod_linespec's. */
int epp_gpiod_parse(const char *spec, char *chip, size_t chiplen, unsigned *offsets, int *n,
                    uint32_t *timeout_ns, char *err, size_t errlen);
int epp_gpiod_parse(const char *spec, char *chip, size_t chiplen, unsigned *offsets, int *n,
                    uint32_t *timeout_ns, char *err, size_t errlen)
{
    struct gpiod_linespec ls;
    unsigned long timeout_us = 0;
    const struct gpiod_linespec_opt opt = {"timeout_us", 1, 1000000, &timeout_us};
    int r = gpiod_linespec_parse(spec, "gpiod port", role_name, EPP_GPIO_NLINES, 0, &opt, 1, &ls,
                                 err, errlen);
    if (r)
        return r;
    if (ls.n != 12 && ls.n != 13) {
        snprintf(err, errlen,
                 "gpiod port '%s': need 12 line offsets (D0-D7, nWrite, nDataStr, nAddrStr, "
                 "nWait) or 13 (+ nInit), got %d",
                 spec, ls.n);
        return -EINVAL;
    }
    snprintf(chip, chiplen, "%s", ls.chip);
    for (int i = 0; i < ls.n; i++)
        offsets[i] = (unsigned)ls.offset[i];
    *n = ls.n;
    if (timeout_us)
        *timeout_ns = (uint32_t)(timeout_us * 1000u);
    return 0;
}

int epp_gpiod_lines_open(struct epp_gpio_lines *lines, const char *spec, uint32_t *timeout_ns,
                         char *err, size_t errlen)
{
    char chip[128];
    unsigned off[EPP_GPIO_NLINES];
    int n = 0, r;
    r = epp_gpiod_parse(spec, chip, sizeof(chip), off, &n, timeout_ns, err, errlen);
    if (r)
        return r;
    struct lines_priv *p = calloc(1, sizeof(*p));
    if (!p) {
        snprintf(err, errlen, "gpiod port '%s': out of memory", spec);
        return -ENOMEM;
    }
    p->nlines = n;
    p->chip = gpiod_chip_open_lookup(chip);
    if (!p->chip) {
        r = -errno ? -errno : -ENODEV;
        snprintf(err, errlen, "gpiod port '%s': cannot open GPIO chip '%s': %s", spec, chip,
                 strerror(-r));
        goto fail;
    }
    for (int i = 0; i < n; i++) {
        p->line[i] = gpiod_chip_get_line(p->chip, off[i]);
        if (!p->line[i]) {
            r = -errno ? -errno : -EINVAL;
            snprintf(err, errlen, "gpiod port '%s': chip %s has no line %u (%s): %s", spec, chip,
                     off[i], role_name[i], strerror(-r));
            goto fail;
        }
        int rr = i == EPP_GPIO_NWAIT || i < 8
                     ? gpiod_line_request_input(p->line[i], CONSUMER)
                     : gpiod_line_request_output(p->line[i], CONSUMER, 1);
        if (rr) {
            r = -errno ? -errno : -EBUSY;
            snprintf(err, errlen, "gpiod port '%s': cannot request line %u (%s): %s", spec,
                     off[i], role_name[i], strerror(-r));
            goto fail;
        }
    }
    gpiod_line_bulk_init(&p->data);
    for (int i = 0; i < 8; i++)
        gpiod_line_bulk_add(&p->data, p->line[i]);
    memset(lines, 0, sizeof(*lines));
    lines->data_dir = l_data_dir;
    lines->data_set = l_data_set;
    lines->data_get = l_data_get;
    lines->set = l_set;
    lines->get = l_get;
    lines->now_ns = l_now;
    lines->close = l_close;
    lines->ctx = p;
    lines->has_ninit = n == 13;
    return 0;
fail:
    l_close(p);
    return r;
}
