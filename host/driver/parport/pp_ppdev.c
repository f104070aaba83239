/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pp_ppdev.c - the parallel port through the kernel's ppdev (/dev/parportN):
 * no root needed, only access to the device node.  The port is claimed
 * exclusively (PPEXCL, PPCLAIM) for as long as it is open.
 *
 * PPWCONTROL carries control bits 0-3 only; the data direction (bit 5) is
 * PPDATADIR.  Both are sent only when they change.  Linux answers PPRCONTROL
 * from its software copy of the register, not from the pins, so x mode
 * (control pins as inputs) is refused here.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <linux/parport.h>
#include <sys/ioctl.h>

#include <linux/ppdev.h>

#include "pp_port.h"

struct ppdev_priv {
    struct epp_ppdev_sys sys;
    int fd;
    int control; /* bits 0-3 as last written, -1 unknown */
    int dir;     /* data direction as last set, -1 unknown */
};

static int ctl(struct ppdev_priv *d, unsigned long req, void *arg)
{
    return d->sys.ioctl(d->sys.ctx, d->fd, req, arg);
}

static int pd_begin(struct pp_port *p)
{
    (void)p;
    return 0;
}

static int pd_read_data(struct pp_port *p, uint8_t *v)
{
    unsigned char b = 0;
    int r = ctl(p->priv, PPRDATA, &b);
    *v = b;
    return r;
}

static int pd_write_data(struct pp_port *p, uint8_t v)
{
    unsigned char b = v;
    return ctl(p->priv, PPWDATA, &b);
}

static int pd_read_status(struct pp_port *p, uint8_t *v)
{
    unsigned char b = 0;
    int r = ctl(p->priv, PPRSTATUS, &b);
    *v = b;
    return r;
}

static int pd_read_control(struct pp_port *p, uint8_t *v)
{
    struct ppdev_priv *d = p->priv;
    unsigned char b = 0;
    int r = ctl(d, PPRCONTROL, &b);
    *v = (uint8_t)((b & 0x0fu) | (d->dir > 0 ? PP_CTRL_DIR : 0u));
    return r;
}

static int pd_write_control(struct pp_port *p, uint8_t v)
{
    struct ppdev_priv *d = p->priv;
    int r = 0;
    int c = v & 0x0f, dir = (v & PP_CTRL_DIR) ? 1 : 0;
    if (c != d->control) {
        unsigned char b = (unsigned char)c;
        r = ctl(d, PPWCONTROL, &b);
        if (r)
            return r;
        d->control = c;
    }
    if (dir != d->dir) {
        r = ctl(d, PPDATADIR, &dir);
        if (r)
            return r;
        d->dir = dir;
    }
    return 0;
}

static void pd_close(struct pp_port *p)
{
    struct ppdev_priv *d = p->priv;
    if (!d)
        return;
    ctl(d, PPRELEASE, NULL);
    d->sys.close(d->sys.ctx, d->fd);
    free(d);
    p->priv = NULL;
}

static const struct pp_ops ppdev_ops = {pd_begin,        pd_read_data,    pd_write_data,
                                        pd_read_status,  pd_read_control, pd_write_control,
                                        pd_close};

int pp_ppdev_claim(const struct epp_ppdev_sys *sys, const char *path, char *err, size_t errlen)
{
    int fd = sys->open(sys->ctx, path, O_RDWR);
    if (fd < 0) {
        snprintf(err, errlen, "ppdev %s: open failed: %s", path, strerror(-fd));
        return fd;
    }
    int r = sys->ioctl(sys->ctx, fd, PPEXCL, NULL);
    if (!r)
        r = sys->ioctl(sys->ctx, fd, PPCLAIM, NULL);
    if (r) {
        snprintf(err, errlen, "ppdev %s: cannot claim the port: %s%s", path, strerror(-r),
                 r == -EBUSY ? " (the port is busy: another driver or program uses it)" : "");
        sys->close(sys->ctx, fd);
        return r;
    }
    return fd;
}

static int set_mode(struct ppdev_priv *d, enum pp_mode mode)
{
    int m = mode == PP_MODE_IN    ? IEEE1284_MODE_BYTE
            : mode == PP_MODE_EPP ? IEEE1284_MODE_EPP
                                  : IEEE1284_MODE_COMPAT;
    int r = ctl(d, PPSETMODE, &m);
    if (r)
        return r;
    int dir = mode == PP_MODE_IN;
    r = ctl(d, PPDATADIR, &dir);
    if (!r)
        d->dir = dir;
    return r;
}

int pp_ppdev_open(struct pp_port *p, const struct epp_ppdev_sys *sys, const char *path,
                  enum pp_mode mode, char *err, size_t errlen)
{
    if (mode == PP_MODE_X) {
        snprintf(err, errlen,
                 "ppdev %s: x mode needs the control pins' levels, which ppdev does not "
                 "report (it answers from a software copy); use the port's I/O address "
                 "(raw port I/O) for x mode",
                 path);
        return -EINVAL;
    }
    struct ppdev_priv *d = calloc(1, sizeof(*d));
    if (!d) {
        snprintf(err, errlen, "ppdev %s: out of memory", path);
        return -ENOMEM;
    }
    d->sys = *sys;
    d->control = -1;
    d->dir = -1;
    d->fd = pp_ppdev_claim(sys, path, err, errlen);
    if (d->fd < 0) {
        int r = d->fd;
        free(d);
        return r;
    }
    snprintf(p->name, sizeof(p->name), "ppdev %s", path);
    p->kind = "ppdev";
    p->ops = &ppdev_ops;
    p->priv = d;
    p->mode = mode;
    int r = set_mode(d, mode);
    if (r) {
        snprintf(err, errlen, "ppdev %s: cannot set the port to %s mode: %s", path,
                 mode == PP_MODE_IN ? "byte (input)" : mode == PP_MODE_EPP ? "EPP" : "SPP",
                 strerror(-r));
        pd_close(p);
        return r;
    }
    return 0;
}
