/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of hal_parport's port layer (host/driver/parport): the cfg
 * parser, the raw backend (on the virtual port's register model, through
 * an instruction layer that counts ioperm per thread), ppdev against a
 * recorded system-call layer, gpiod against simulated lines, and how
 * pp_open picks a backend from a cfg address.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <linux/parport.h>
#include <linux/ppdev.h>

#include "../check.h"
#include "hm2/gpiod_linespec.h"
#include "pp_cfg.h"
#include "pp_port.h"
#include "vpp.h"

int pp_gpiod_parse(const char *spec, struct gpiod_linespec *ls, char *err, size_t errlen);

static char dir[64];

/* ---- cfg ------------------------------------------------------------------ */

static void test_cfg_good(void)
{
    struct pp_cfg c;
    char err[600];
    CHECK_EQ_INT(pp_cfg_parse("0x278 0x378 in 0x20A0 out", &c, err, sizeof(err)), 0);
    CHECK_EQ_INT(c.n, 3);
    CHECK_EQ_INT(c.port[0].kind, PP_ADDR_IO);
    CHECK_EQ_INT(c.port[0].addr, 0x278);
    CHECK_EQ_INT(c.port[0].mode, PP_MODE_OUT);
    CHECK_EQ_INT(c.port[0].hi, 0);
    CHECK_EQ_INT(c.port[1].mode, PP_MODE_IN);
    CHECK_EQ_INT(c.port[2].addr, 0x20a0);
    CHECK_EQ_INT(pp_cfg_parse(" 0 out\t1 in \n", &c, err, sizeof(err)), 0);
    CHECK_EQ_INT(c.n, 2);
    CHECK_EQ_INT(c.port[0].kind, PP_ADDR_INDEX);
    CHECK_EQ_INT(c.port[1].addr, 1);
    CHECK_EQ_INT(pp_cfg_parse("0x0378 956 epp 15 x", &c, err, sizeof(err)), 0);
    CHECK_EQ_INT(c.port[0].addr, 0x378);
    CHECK_EQ_INT(c.port[1].addr, 0x3bc); /* decimal, as C reads it */
    CHECK_EQ_INT(c.port[1].kind, PP_ADDR_IO);
    CHECK_EQ_INT(c.port[1].mode, PP_MODE_EPP);
    CHECK_EQ_INT(c.port[2].kind, PP_ADDR_INDEX);
    CHECK_EQ_INT(c.port[2].mode, PP_MODE_X);
    CHECK_EQ_INT(pp_cfg_parse("raw:0xd000,0xd010 in raw:0x3bc,none ppdev:/dev/parport1 "
                              "gpiod:gpiochip0:lines=1/2 sim:/tmp/a x",
                              &c, err, sizeof(err)),
                 0);
    CHECK_EQ_INT(c.n, 5);
    CHECK_EQ_INT(c.port[0].kind, PP_ADDR_RAW);
    CHECK_EQ_INT(c.port[0].addr, 0xd000);
    CHECK_EQ_INT(c.port[0].hi, 0xd010);
    CHECK_EQ_INT(c.port[1].hi, -1);
    CHECK_EQ_STR(c.port[2].spec, "/dev/parport1");
    CHECK_EQ_STR(c.port[3].spec, "gpiochip0:lines=1/2");
    CHECK_EQ_STR(c.port[4].spec, "/tmp/a");
    CHECK_EQ_INT(c.port[4].mode, PP_MODE_X);
    CHECK_EQ_STR(c.port[4].text, "sim:/tmp/a");
    CHECK_EQ_INT(pp_cfg_parse("0 1 2 3 4 5 6 7", &c, err, sizeof(err)), 0);
    CHECK_EQ_INT(c.n, 8);
    CHECK_EQ_STR(pp_mode_name(PP_MODE_EPP), "epp");
}

static void bad(const char *cfg, const char *msg)
{
    struct pp_cfg c;
    char err[600] = "";
    CHECK_EQ_INT(pp_cfg_parse(cfg, &c, err, sizeof(err)), -EINVAL);
    if (!strstr(err, msg))
        fprintf(stderr, "cfg '%s': got '%s', want '%s'\n", cfg, err, msg);
    CHECK(strstr(err, msg) != NULL);
}

static void test_cfg_bad(void)
{
    bad("", "no ports configured");
    bad("   ", "no ports configured");
    bad(NULL, "no ports configured");
    bad("out", "type 'out' must follow a port address");
    bad("0x378 in x", "one type per port");
    bad("0378", "bad port address '0378'"); /* octal 8 */
    bad("-1", "bad port address '-1'");
    bad("0x", "bad port address '0x'");
    bad("0x378in", "bad port address '0x378in'");
    bad("0x1fffe", "bad port address");
    bad("raw:", "bad raw port");
    bad("raw:12", "bad raw port"); /* < 16 */
    bad("raw:0x378,", "bad raw port");
    bad(":x", "unknown port kind");
    bad("usb:1", "unknown port kind in 'usb:1'");
    bad("ppdev:", "names nothing after the ':'");
    bad("0 0", "given twice");
    bad("0x378 raw:888", "given twice");
    bad("sim:a sim:a", "given twice");
    bad("0 1 2 3 4 5 6 7 8", "more than 8 ports ('8')");
    char longw[400];
    memset(longw, 'a', sizeof(longw) - 1);
    longw[sizeof(longw) - 1] = '\0';
    bad(longw, "is too long");
}

/* ---- raw backend on the virtual port --------------------------------------- */

struct fio {
    struct vpp_state *st;
    int ioperm_calls;
    int fail;              /* ioperm result when nonzero */
    unsigned long granted; /* last range granted */
};

static int f_ioperm(void *ctx, unsigned long from, unsigned long num, int on)
{
    struct fio *f = ctx;
    (void)num;
    if (f->fail)
        return f->fail;
    if (on) {
        f->ioperm_calls++;
        f->granted = from;
    }
    return 0;
}

static uint8_t f_inb(void *ctx, unsigned long port)
{
    struct fio *f = ctx;
    return vpp_inb(f->st, (unsigned)(port - 0x378), 0);
}

static void f_outb(void *ctx, uint8_t v, unsigned long port)
{
    struct fio *f = ctx;
    vpp_outb(f->st, (unsigned)(port - 0x378), v, 0);
}

static struct vpp_state *vport(const char *name, unsigned opts)
{
    char path[128], err[600];
    struct vpp_state *st = NULL;
    snprintf(path, sizeof(path), "%s/%s", dir, name);
    CHECK_EQ_INT(vpp_create(path, opts, 1, err, sizeof(err)), 0);
    CHECK_EQ_INT(vpp_open(path, &st, err, sizeof(err)), 0);
    return st;
}

static void *begin_in_thread(void *arg)
{
    struct pp_port *p = arg;
    p->ops->begin(p);
    p->ops->begin(p);
    return NULL;
}

static void test_raw_threads(void)
{
    struct fio f = {vport("raw1", 0), 0, 0, 0};
    struct epp_raw_io io = {f_ioperm, f_inb, NULL, NULL, f_outb, NULL, NULL, &f};
    struct pp_port p;
    char err[600];
    memset(&p, 0, sizeof(p));
    CHECK_EQ_INT(pp_raw_open(&p, &io, NULL, 0x378, 0, -1, PP_MODE_OUT, err, sizeof(err)), 0);
    CHECK_EQ_STR(p.kind, "raw");
    CHECK_EQ_STR(p.name, "0x378");
    CHECK_EQ_INT(f.ioperm_calls, 1);
    CHECK_EQ_INT(f.st->writes[VPP_REG_ECR] + f.st->reads[VPP_REG_ECR], 0); /* out: no ECR */
    CHECK_EQ_INT(f.st->writes[VPP_REG_CONTROL] + f.st->writes[VPP_REG_DATA], 0);
    CHECK_EQ_INT(p.ops->begin(&p), 0); /* the opening thread has permission */
    CHECK_EQ_INT(f.ioperm_calls, 1);
    pthread_t t;
    pthread_create(&t, NULL, begin_in_thread, &p);
    pthread_join(t, NULL);
    CHECK_EQ_INT(f.ioperm_calls, 2); /* once for the new thread */
    uint8_t v;
    p.ops->write_data(&p, 0x3c);
    p.ops->read_data(&p, &v);
    CHECK_EQ_INT(v, 0x3c);
    p.ops->write_control(&p, 0x0b);
    p.ops->read_control(&p, &v);
    CHECK_EQ_INT(v, 0xcb);
    vpp_drive(f.st, 11, 0);
    p.ops->read_status(&p, &v);
    CHECK_EQ_INT(v & 0x80, 0x80);
    pp_close(&p);
    vpp_close(f.st);

    f.fail = -EPERM;
    CHECK_EQ_INT(pp_raw_open(&p, &io, NULL, 0x378, 0, -1, PP_MODE_OUT, err, sizeof(err)),
                 -EPERM);
    CHECK(strstr(err, "ioperm(0x378, 3) failed: Operation not permitted (needs root or "
                      "CAP_SYS_RAWIO)") != NULL);
    struct epp_raw_io none = {0};
    CHECK_EQ_INT(pp_raw_open(&p, &none, NULL, 0x378, 0, -1, PP_MODE_OUT, err, sizeof(err)),
                 -ENOSYS);
}

static void test_raw_modes(void)
{
    char err[600];
    struct pp_port p;
    /* in on an ECP port: PS/2 mode, direction bit, control pins kept */
    struct fio f = {vport("raw2", VPP_OPT_ECR), 0, 0, 0};
    struct epp_raw_io io = {f_ioperm, f_inb, NULL, NULL, f_outb, NULL, NULL, &f};
    vpp_outb(f.st, 2, 0x03, 0);
    memset(&p, 0, sizeof(p));
    CHECK_EQ_INT(pp_raw_open(&p, &io, NULL, 0x378, 0, -1, PP_MODE_IN, err, sizeof(err)), 0);
    CHECK_EQ_INT(f.st->ecr, 0x34);
    CHECK_EQ_INT(f.st->control_latch, 0x23);
    pp_close(&p);
    /* epp: EPP mode; an explicit ECR address is used as given */
    memset(&p, 0, sizeof(p));
    CHECK_EQ_INT(pp_raw_open(&p, &io, NULL, 0x378, 0x778, -1, PP_MODE_EPP, err, sizeof(err)),
                 0);
    CHECK_EQ_INT(f.st->ecr, 0x94);
    pp_close(&p);
    /* hi = -1: the ECR is never touched */
    uint64_t before = f.st->writes[VPP_REG_ECR] + f.st->reads[VPP_REG_ECR];
    memset(&p, 0, sizeof(p));
    CHECK_EQ_INT(pp_raw_open(&p, &io, NULL, 0x378, -1, -1, PP_MODE_EPP, err, sizeof(err)), 0);
    CHECK_EQ_INT(f.st->writes[VPP_REG_ECR] + f.st->reads[VPP_REG_ECR], before);
    pp_close(&p);
    /* x: control pins released */
    memset(&p, 0, sizeof(p));
    CHECK_EQ_INT(pp_raw_open(&p, &io, NULL, 0x378, 0, -1, PP_MODE_X, err, sizeof(err)), 0);
    CHECK_EQ_INT(f.st->control_latch, PP_CTRL_RELEASED);
    pp_close(&p);
    vpp_close(f.st);
    /* no ECR: probed (reads 0xff), not written */
    f.st = vport("raw3", 0);
    memset(&p, 0, sizeof(p));
    CHECK_EQ_INT(pp_raw_open(&p, &io, NULL, 0x378, 0, -1, PP_MODE_IN, err, sizeof(err)), 0);
    CHECK_EQ_INT(f.st->reads[VPP_REG_ECR], 1);
    CHECK_EQ_INT(f.st->writes[VPP_REG_ECR], 0);
    pp_close(&p);
    vpp_close(f.st);
}

/* ---- ppdev ---------------------------------------------------------------- */

struct fppdev {
    unsigned long req[64];
    int arg[64];
    int n;
    int open_err, claim_err, excl_err;
    int fd_open, closed;
    char path[128];
    unsigned char status;
};

static int fp_open(void *ctx, const char *path, int flags)
{
    struct fppdev *f = ctx;
    (void)flags;
    snprintf(f->path, sizeof(f->path), "%s", path);
    if (f->open_err)
        return f->open_err;
    f->fd_open = 1;
    return 7;
}

static int fp_close(void *ctx, int fd)
{
    struct fppdev *f = ctx;
    CHECK_EQ_INT(fd, 7);
    f->closed++;
    f->fd_open = 0;
    return 0;
}

static int fp_ioctl(void *ctx, int fd, unsigned long req, void *arg)
{
    struct fppdev *f = ctx;
    CHECK_EQ_INT(fd, 7);
    if (f->n < 64) {
        f->req[f->n] = req;
        f->arg[f->n] = -1;
        if (req == PPWCONTROL || req == PPWDATA)
            f->arg[f->n] = *(unsigned char *)arg;
        else if (req == PPDATADIR || req == PPSETMODE)
            f->arg[f->n] = *(int *)arg;
        f->n++;
    }
    if (req == PPEXCL && f->excl_err)
        return f->excl_err;
    if (req == PPCLAIM && f->claim_err)
        return f->claim_err;
    if (req == PPRSTATUS)
        *(unsigned char *)arg = f->status;
    if (req == PPRDATA || req == PPRCONTROL)
        *(unsigned char *)arg = 0x5a;
    return 0;
}

static struct epp_ppdev_sys fppdev_sys(struct fppdev *f)
{
    struct epp_ppdev_sys s = {fp_open, fp_close, fp_ioctl, NULL, NULL, f};
    return s;
}

static void test_ppdev(void)
{
    struct fppdev f;
    memset(&f, 0, sizeof(f));
    struct epp_ppdev_sys sys = fppdev_sys(&f);
    struct pp_port p;
    char err[600];
    memset(&p, 0, sizeof(p));
    CHECK_EQ_INT(pp_ppdev_open(&p, &sys, "/dev/parport0", PP_MODE_OUT, err, sizeof(err)), 0);
    CHECK_EQ_STR(p.name, "ppdev /dev/parport0");
    CHECK_EQ_INT(f.n, 4);
    CHECK(f.req[0] == PPEXCL && f.req[1] == PPCLAIM && f.req[2] == PPSETMODE &&
          f.req[3] == PPDATADIR);
    CHECK_EQ_INT(f.arg[2], IEEE1284_MODE_COMPAT);
    CHECK_EQ_INT(f.arg[3], 0);
    f.n = 0;
    p.ops->write_control(&p, 0x0b);
    p.ops->write_control(&p, 0x0b); /* unchanged: nothing sent */
    p.ops->write_control(&p, 0x2b); /* only the direction changed */
    CHECK_EQ_INT(f.n, 2);
    CHECK(f.req[0] == PPWCONTROL && f.arg[0] == 0x0b);
    CHECK(f.req[1] == PPDATADIR && f.arg[1] == 1);
    f.n = 0;
    uint8_t v;
    f.status = 0x87;
    p.ops->read_status(&p, &v);
    CHECK_EQ_INT(v, 0x87);
    p.ops->write_data(&p, 0xc3);
    CHECK(f.req[1] == PPWDATA && f.arg[1] == 0xc3);
    p.ops->read_control(&p, &v);
    CHECK_EQ_INT(v, 0x0a | 0x20); /* bits 0-3 from Linux, the direction we set */
    pp_close(&p);
    CHECK(f.req[f.n - 1] == PPRELEASE);
    CHECK_EQ_INT(f.closed, 1);

    /* in mode: byte mode, reverse direction; epp mode: EPP */
    memset(&f, 0, sizeof(f));
    CHECK_EQ_INT(pp_ppdev_open(&p, &sys, "/dev/parport1", PP_MODE_IN, err, sizeof(err)), 0);
    CHECK_EQ_INT(f.arg[2], IEEE1284_MODE_BYTE);
    CHECK_EQ_INT(f.arg[3], 1);
    pp_close(&p);
    memset(&f, 0, sizeof(f));
    CHECK_EQ_INT(pp_ppdev_open(&p, &sys, "/dev/parport1", PP_MODE_EPP, err, sizeof(err)), 0);
    CHECK_EQ_INT(f.arg[2], IEEE1284_MODE_EPP);
    pp_close(&p);

    /* busy, missing, x mode */
    memset(&f, 0, sizeof(f));
    f.claim_err = -EBUSY;
    CHECK_EQ_INT(pp_ppdev_open(&p, &sys, "/dev/parport0", PP_MODE_OUT, err, sizeof(err)),
                 -EBUSY);
    CHECK(strstr(err, "ppdev /dev/parport0: cannot claim the port: Device or resource busy "
                      "(the port is busy") != NULL);
    CHECK_EQ_INT(f.closed, 1);
    memset(&f, 0, sizeof(f));
    f.open_err = -EACCES;
    CHECK_EQ_INT(pp_ppdev_open(&p, &sys, "/dev/parport0", PP_MODE_OUT, err, sizeof(err)),
                 -EACCES);
    CHECK(strstr(err, "open failed: Permission denied") != NULL);
    memset(&f, 0, sizeof(f));
    CHECK_EQ_INT(pp_ppdev_open(&p, &sys, "/dev/parport0", PP_MODE_X, err, sizeof(err)), -EINVAL);
    CHECK_EQ_INT(f.n, 0);
    CHECK_EQ_STR(f.path, "");
}

/* ---- gpiod ---------------------------------------------------------------- */

struct flines {
    int level[18], out[18], od[18], configured[18];
    uint32_t wired;
    int sets, config_err_pin;
};

static int fl_config(void *ctx, int pin, int out, int od, int level)
{
    struct flines *f = ctx;
    if (pin == f->config_err_pin)
        return -EBUSY;
    f->configured[pin] = 1;
    f->out[pin] = out;
    f->od[pin] = od;
    if (out)
        f->level[pin] = level;
    return 0;
}

static int fl_set(void *ctx, int pin, int level)
{
    struct flines *f = ctx;
    CHECK(f->out[pin]);
    f->sets++;
    f->level[pin] = level;
    return 0;
}

static int fl_get(void *ctx, int pin, int *level)
{
    struct flines *f = ctx;
    *level = f->level[pin];
    return 0;
}

static int fl_has(void *ctx, int pin)
{
    struct flines *f = ctx;
    return (f->wired >> pin) & 1u;
}

static struct pp_gpio_lines flines(struct flines *f)
{
    struct pp_gpio_lines l = {fl_config, fl_set, fl_get, fl_has, NULL, f};
    return l;
}

static void test_gpiod(void)
{
    struct flines f;
    memset(&f, 0, sizeof(f));
    f.wired = 0x3fffe & ~(1u << 12); /* pins 1..17, pin 12 not wired */
    struct pp_gpio_lines l = flines(&f);
    struct pp_port p;
    char err[600];
    memset(&p, 0, sizeof(p));
    CHECK_EQ_INT(pp_gpiod_open(&p, &l, "chip:x", PP_MODE_OUT, err, sizeof(err)), 0);
    CHECK_EQ_STR(p.name, "gpiod chip:x");
    for (int n = 2; n <= 9; n++)
        CHECK(f.out[n]);
    CHECK(!f.out[10] && !f.out[11] && !f.out[13] && !f.out[15]);
    CHECK(f.out[1] && f.out[14] && f.out[16] && f.out[17] && !f.od[1]);
    CHECK(!f.configured[12]);
    p.ops->write_data(&p, 0xa5);
    CHECK_EQ_INT(f.level[2], 1);
    CHECK_EQ_INT(f.level[3], 0);
    CHECK_EQ_INT(f.level[9], 1);
    int sets = f.sets;
    p.ops->write_data(&p, 0xa5);
    CHECK_EQ_INT(f.sets, sets); /* unchanged lines are not written */
    p.ops->write_control(&p, 0x00);
    CHECK_EQ_INT(f.level[1], 1);
    CHECK_EQ_INT(f.level[14], 1);
    CHECK_EQ_INT(f.level[16], 0);
    CHECK_EQ_INT(f.level[17], 1);
    uint8_t v;
    f.level[10] = 1, f.level[11] = 0, f.level[13] = 0, f.level[15] = 1;
    p.ops->read_status(&p, &v);
    /* 11 low -> bit 7 set; 12 not wired reads high -> bit 5 */
    CHECK_EQ_INT(v, 0x80 | 0x40 | 0x20 | 0x08 | 0x06);
    p.ops->read_data(&p, &v);
    CHECK_EQ_INT(v, 0xa5);
    pp_close(&p);

    /* x mode: control lines open drain, read back with the inversions */
    memset(&f, 0, sizeof(f));
    f.wired = 0x3fffe;
    l = flines(&f);
    CHECK_EQ_INT(pp_gpiod_open(&p, &l, "c", PP_MODE_X, err, sizeof(err)), 0);
    CHECK(f.od[1] && f.od[14] && f.od[16] && f.od[17] && f.level[1] == 1);
    f.level[1] = 0, f.level[14] = 1, f.level[16] = 0, f.level[17] = 1;
    p.ops->read_control(&p, &v);
    CHECK_EQ_INT(v & 0x0f, 0x01);
    pp_close(&p);

    /* in mode: data lines are inputs, writes only latch */
    memset(&f, 0, sizeof(f));
    f.wired = 0x3fffe;
    l = flines(&f);
    CHECK_EQ_INT(pp_gpiod_open(&p, &l, "c", PP_MODE_IN, err, sizeof(err)), 0);
    CHECK(!f.out[2] && !f.out[9]);
    p.ops->write_data(&p, 0xff);
    CHECK_EQ_INT(f.sets, 0);
    f.level[3] = 1, f.level[9] = 1;
    p.ops->read_data(&p, &v);
    CHECK_EQ_INT(v, 0x82);
    pp_close(&p);

    /* a line that cannot be requested */
    memset(&f, 0, sizeof(f));
    f.wired = 0x3fffe;
    f.config_err_pin = 13;
    l = flines(&f);
    CHECK_EQ_INT(pp_gpiod_open(&p, &l, "c", PP_MODE_OUT, err, sizeof(err)), -EBUSY);
    CHECK(strstr(err, "cannot request the line of pin 13 as input") != NULL);

    struct gpiod_linespec ls;
    CHECK_EQ_INT(pp_gpiod_parse("gpiochip1:lines=2/3/4/5/6/7/8/9/10/11/12/13/14/15/16/-/-", &ls,
                                err, sizeof(err)),
                 0);
    CHECK_EQ_STR(ls.chip, "gpiochip1");
    CHECK_EQ_INT(ls.offset[0], 2);
    CHECK_EQ_INT(ls.offset[16], GPIOD_LINESPEC_NC);
    CHECK_EQ_INT(pp_gpiod_parse("c:1,2", &ls, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "need 17 line offsets") != NULL);
    CHECK_EQ_INT(pp_gpiod_parse("c:-/-/-/-/-/-/-/-/-/-/-/-/-/-/-/-/-/-", &ls, err, sizeof(err)),
                 -EINVAL);
    CHECK(strstr(err, "more than 17 line offsets") != NULL);
    CHECK_EQ_INT(pp_gpiod_parse("c:1/2/3/4/5/6/7/8/9/10/11/12/13/14/15/16/17:timeout_us=5", &ls,
                                err, sizeof(err)),
                 -EINVAL);
    CHECK(strstr(err, "unknown option 'timeout_us=5'") != NULL);
}

/* ---- choosing a backend --------------------------------------------------- */

struct fsys {
    long base[16];
    int dev[16];
};

static long fs_base(void *ctx, int i)
{
    struct fsys *s = ctx;
    return s->base[i] ? s->base[i] : -ENOENT;
}

static int fs_dev(void *ctx, int i)
{
    struct fsys *s = ctx;
    return s->dev[i];
}

static void test_open_dispatch(void)
{
    struct fio f = {vport("disp", 0), 0, 0, 0};
    struct epp_raw_io io = {f_ioperm, f_inb, NULL, NULL, f_outb, NULL, NULL, &f};
    struct fppdev fp;
    memset(&fp, 0, sizeof(fp));
    struct epp_ppdev_sys ps = fppdev_sys(&fp);
    struct fsys fs;
    memset(&fs, 0, sizeof(fs));
    fs.base[0] = 0x378, fs.dev[0] = 1;
    fs.base[1] = 0x378; /* no /dev/parport1 */
    const struct pp_sys sys = {&io, &ps, fs_base, fs_dev, &fs};
    struct pp_cfg c;
    struct pp_port p;
    char err[600];

    /* N with /dev/parportN: ppdev */
    pp_cfg_parse("0", &c, err, sizeof(err));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), 0);
    CHECK_EQ_STR(p.kind, "ppdev");
    CHECK_EQ_STR(fp.path, "/dev/parport0");
    pp_close(&p);
    /* N in x mode: raw at Linux's address, ppdev claim held until close */
    memset(&fp, 0, sizeof(fp));
    pp_cfg_parse("0 x", &c, err, sizeof(err));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), 0);
    CHECK_EQ_STR(p.kind, "raw");
    CHECK_EQ_STR(p.name, "0x378");
    CHECK(fp.fd_open && fp.req[1] == PPCLAIM);
    pp_close(&p);
    CHECK(!fp.fd_open && fp.req[fp.n - 1] == PPRELEASE);
    /* N without a device node: raw at Linux's address, with a note */
    pp_cfg_parse("1", &c, err, sizeof(err));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), 0);
    CHECK_EQ_STR(p.kind, "raw");
    CHECK(strstr(p.note, "no /dev/parport1, raw port I/O at 0x378") != NULL);
    pp_close(&p);
    /* N unknown */
    pp_cfg_parse("2", &c, err, sizeof(err));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), -ENODEV);
    CHECK(strstr(err, "Linux parallel port 2 not found") != NULL);
    /* an address Linux owns: claimed, raw I/O; busy refused before any I/O */
    memset(&fp, 0, sizeof(fp));
    pp_cfg_parse("0x378", &c, err, sizeof(err));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), 0);
    CHECK_EQ_STR(p.kind, "raw");
    CHECK(fp.fd_open);
    CHECK_EQ_STR(p.note, "");
    pp_close(&p);
    memset(&fp, 0, sizeof(fp));
    fp.claim_err = -EBUSY;
    f.ioperm_calls = 0;
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), -EBUSY);
    CHECK(strstr(err, "the port is busy") != NULL);
    CHECK_EQ_INT(f.ioperm_calls, 0);
    /* an address Linux does not know: raw without a claim, with a note */
    pp_cfg_parse("0x3bc", &c, err, sizeof(err));
    memset(&fp, 0, sizeof(fp));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), 0);
    CHECK(strstr(p.note, "no Linux parport registered at 0x3bc") != NULL);
    CHECK_EQ_INT(fp.n, 0);
    pp_close(&p);
    /* raw: never claims */
    pp_cfg_parse("raw:0x378", &c, err, sizeof(err));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), 0);
    CHECK_EQ_INT(fp.n, 0);
    pp_close(&p);
    vpp_close(f.st);

    /* in mode on a port whose drivers stay on is refused, and closed */
    char path[160], cfg[200];
    snprintf(path, sizeof(path), "%s/spp", dir);
    CHECK_EQ_INT(vpp_create(path, VPP_OPT_NO_BIDIR, 1, err, sizeof(err)), 0);
    snprintf(cfg, sizeof(cfg), "sim:%s in", path);
    pp_cfg_parse(cfg, &c, err, sizeof(err));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &sys, NULL, err, sizeof(err)), -ENODEV);
    CHECK(strstr(err, "cannot be an input port") != NULL);
    struct vpp_state *st;
    CHECK_EQ_INT(vpp_open(path, &st, err, sizeof(err)), 0);
    CHECK_EQ_INT(st->owner_pid, 0);
    vpp_close(st);
}

static long long fake_clock(void)
{
    return 12345;
}

unsigned long pp_sim_unpermitted(const struct pp_port *p);

static void test_sim_backend(void)
{
    char path[160], cfg[200], err[600];
    struct pp_cfg c;
    struct pp_port p, q;
    snprintf(path, sizeof(path), "%s/simb", dir);
    CHECK_EQ_INT(vpp_create(path, VPP_OPT_ECR, 1, err, sizeof(err)), 0);
    snprintf(cfg, sizeof(cfg), "sim:%s epp", path);
    pp_cfg_parse(cfg, &c, err, sizeof(err));
    CHECK_EQ_INT(pp_open(&p, &c.port[0], &pp_sys_linux, fake_clock, err, sizeof(err)), 0);
    CHECK_EQ_STR(p.kind, "sim");
    CHECK_EQ_INT(pp_open(&q, &c.port[0], &pp_sys_linux, fake_clock, err, sizeof(err)), -EBUSY);
    CHECK(strstr(err, "claimed by this process") != NULL);
    p.ops->begin(&p);
    p.ops->write_data(&p, 0x81);
    p.stamp_floor = 20000;
    p.ops->write_data(&p, 0x01);
    struct vpp_state *st;
    CHECK_EQ_INT(vpp_open(path, &st, err, sizeof(err)), 0);
    struct vpp_log_entry e[4];
    uint64_t first;
    CHECK_EQ_INT(vpp_log_read(st, 0, e, 4, &first), 2);
    CHECK_EQ_INT(e[0].t_ns, 12345);
    CHECK_EQ_INT(e[1].t_ns, 20000);
    CHECK_EQ_INT(st->ecr, 0x94);
    CHECK_EQ_INT(pp_sim_unpermitted(&p), 0);
    CHECK_EQ_INT(st->owner_pid, getpid());
    pp_close(&p);
    CHECK_EQ_INT(st->owner_pid, 0);
    vpp_close(st);
}

int main(void)
{
    snprintf(dir, sizeof(dir), "/tmp/pppXXXXXX");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    RUN(test_cfg_good);
    RUN(test_cfg_bad);
    RUN(test_raw_threads);
    RUN(test_raw_modes);
    RUN(test_ppdev);
    RUN(test_gpiod);
    RUN(test_open_dispatch);
    RUN(test_sim_backend);
    char cmd[128];
    snprintf(cmd, sizeof(cmd), "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
    return check_summary();
}
