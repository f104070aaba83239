/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pp_open.c - from a cfg address to an open port (pp_port.h, pp_cfg.h).
 *
 *   N            /dev/parportN exists: ppdev (x mode: raw I/O at the port's
 *                address while ppdev holds Linux's claim on it); otherwise
 *                raw I/O at the address Linux found for parportN
 *   0x378        raw I/O; when Linux has a parport at that address, its
 *                ppdev claim is held meanwhile (a busy port is refused)
 *   raw:, ppdev:, gpiod:, sim:   that backend only
 *
 * In "in" mode every backend is checked for data drivers that really turn
 * off (an SPP-only port is refused).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pp_cfg.h"
#include "pp_port.h"

static long sys_linux_base(void *ctx, int index)
{
    (void)ctx;
    char path[80];
    snprintf(path, sizeof(path), "/proc/sys/dev/parport/parport%d/base-addr", index);
    FILE *f = fopen(path, "r");
    if (!f)
        return -ENOENT;
    long base = -ENOENT;
    if (fscanf(f, "%ld", &base) != 1 || base <= 0)
        base = -ENOENT;
    fclose(f);
    return base;
}

static int sys_have_dev(void *ctx, int index)
{
    (void)ctx;
    char path[40];
    snprintf(path, sizeof(path), "/dev/parport%d", index);
    return access(path, F_OK) == 0;
}

const struct pp_sys pp_sys_linux = {&epp_raw_sys_io, &epp_ppdev_sys_libc, sys_linux_base,
                                    sys_have_dev, NULL};

static int open_index(struct pp_port *p, const struct pp_cfg_port *c, const struct pp_sys *sys,
                      char *err, size_t errlen)
{
    int n = (int)c->addr;
    char dev[40];
    snprintf(dev, sizeof(dev), "/dev/parport%d", n);
    long base = sys->linux_base(sys->ctx, n);
    if (sys->have_dev(sys->ctx, n)) {
        if (c->mode != PP_MODE_X)
            return pp_ppdev_open(p, sys->ppdev, dev, c->mode, err, errlen);
        if (base < 0) {
            snprintf(err, errlen,
                     "port %d: x mode needs raw port I/O, but Linux does not say where "
                     "parport%d is (no /proc/sys/dev/parport/parport%d/base-addr)",
                     n, n, n);
            return -ENODEV;
        }
        int fd = pp_ppdev_claim(sys->ppdev, dev, err, errlen);
        if (fd < 0)
            return fd;
        int r = pp_raw_open(p, sys->io, sys->ppdev, (unsigned long)base, 0, fd, c->mode, err,
                            errlen);
        if (r)
            sys->ppdev->close(sys->ppdev->ctx, fd);
        return r;
    }
    if (base < 0) {
        snprintf(err, errlen,
                 "Linux parallel port %d not found (no %s and no "
                 "/proc/sys/dev/parport/parport%d: load the parport_pc and ppdev kernel "
                 "modules, or give the port's I/O address such as 0x378)",
                 n, dev, n);
        return -ENODEV;
    }
    snprintf(p->note, sizeof(p->note), "port %d: no %s, raw port I/O at 0x%lx", n, dev, base);
    return pp_raw_open(p, sys->io, NULL, (unsigned long)base, 0, -1, c->mode, err, errlen);
}

static int open_address(struct pp_port *p, const struct pp_cfg_port *c, const struct pp_sys *sys,
                        char *err, size_t errlen)
{
    int fd = -1;
    for (int n = 0; n < 16; n++) {
        if (sys->linux_base(sys->ctx, n) != c->addr || !sys->have_dev(sys->ctx, n))
            continue;
        char dev[40];
        snprintf(dev, sizeof(dev), "/dev/parport%d", n);
        fd = pp_ppdev_claim(sys->ppdev, dev, err, errlen);
        if (fd < 0)
            return fd;
        break;
    }
    if (fd < 0)
        snprintf(p->note, sizeof(p->note),
                 "no Linux parport registered at 0x%lx, using raw port I/O without a claim",
                 c->addr);
    int r = pp_raw_open(p, sys->io, sys->ppdev, (unsigned long)c->addr, c->hi, fd, c->mode, err,
                        errlen);
    if (r && fd >= 0)
        sys->ppdev->close(sys->ppdev->ctx, fd);
    return r;
}

static int open_gpiod(struct pp_port *p, const struct pp_cfg_port *c, char *err, size_t errlen)
{
    struct pp_gpio_lines l;
    int r = pp_gpiod_lines_open(&l, c->spec, err, errlen);
    if (r)
        return r;
    return pp_gpiod_open(p, &l, c->spec, c->mode, err, errlen);
}

/* The data drivers must be off in "in" mode: a port whose data lines read
 * back two different patterns written to them still drives them. */
static int check_input(struct pp_port *p, char *err, size_t errlen)
{
    uint8_t a = 0, b = 0;
    int r = p->ops->write_data(p, 0x55u);
    if (!r)
        r = p->ops->read_data(p, &a);
    if (!r)
        r = p->ops->write_data(p, 0xaau);
    if (!r)
        r = p->ops->read_data(p, &b);
    if (r) {
        snprintf(err, errlen, "port %s: data register access failed: %s", p->name,
                 strerror(-r));
        return r;
    }
    if (a == 0x55u && b == 0xaau) {
        snprintf(err, errlen,
                 "port %s cannot be an input port: its data lines stay driven with the "
                 "direction bit set (an SPP-only port; choose PS/2, EPP or ECP mode in the "
                 "BIOS)",
                 p->name);
        return -ENODEV;
    }
    return 0;
}

int pp_open(struct pp_port *p, const struct pp_cfg_port *c, const struct pp_sys *sys,
            long long (*clock)(void), char *err, size_t errlen)
{
    int r;
    memset(p, 0, sizeof(*p));
    p->clock = clock;
    switch (c->kind) {
    case PP_ADDR_INDEX:
        r = open_index(p, c, sys, err, errlen);
        break;
    case PP_ADDR_IO:
        r = open_address(p, c, sys, err, errlen);
        break;
    case PP_ADDR_RAW:
        r = pp_raw_open(p, sys->io, NULL, (unsigned long)c->addr, c->hi, -1, c->mode, err,
                        errlen);
        break;
    case PP_ADDR_PPDEV:
        r = pp_ppdev_open(p, sys->ppdev, c->spec, c->mode, err, errlen);
        break;
    case PP_ADDR_GPIOD:
        r = open_gpiod(p, c, err, errlen);
        break;
    case PP_ADDR_SIM:
        r = pp_sim_open(p, c->spec, 0, c->mode, err, errlen);
        break;
    default:
        snprintf(err, errlen, "port '%s': unknown kind", c->text);
        return -EINVAL;
    }
    if (r)
        return r;
    if (c->mode == PP_MODE_IN) {
        r = check_input(p, err, errlen);
        if (r) {
            pp_close(p);
            return r;
        }
    }
    return 0;
}

void pp_close(struct pp_port *p)
{
    if (p->ops && p->ops->close)
        p->ops->close(p);
    p->ops = NULL;
}
