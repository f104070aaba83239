/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * test_jtag.c - the JTAG engine (host/driver/jtag) through its MPSSE cable,
 * with the USB wire replaced by a model of the FTDI chip: the command
 * stream is decoded as FTDI AN_108 defines the commands (data bytes/bits
 * out on -ve and in on +ve edges LSB first, TMS commands with TDI held from
 * bit 7, replies of bit commands in the top bits of a byte, Send Immediate)
 * and drives, pin by pin, a chain of TAPs that follow the IEEE 1149.1 state
 * diagram (written out here independently of the engine's table), with
 * 6-bit instruction registers (capture value 0b000001), IDCODE (0x09) and
 * BYPASS (0x3F), IDCODE selected at Test-Logic-Reset.  A device also
 * models Xilinx configuration (UG380/UG332): JPROGRAM (0x0B) clears it,
 * CFG_IN (0x05) takes the bits shifted through Shift-DR, JSTART (0x0C) and
 * idle clocks start it: DONE comes up when the data held the sync word
 * 0xAA995566, else INIT goes low (CRC error).  The IR capture is
 * 0b0[DONE][INIT]001... as on the parts: bit 5 DONE, bit 4 INIT, bits 1..0 01.
 */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "hm2/jtag.h"
#include "hm2/jtag_gpio.h"
#include "hm2/jtag_mpsse.h"
#include "hm2/jtag_xilinx.h"

/* ---- TAP model ---- */

enum { TLR, RTI, SDS, CDR, SDR, E1D, PDR, E2D, UDR, SIS, CIR, SIR, E1I, PIR, E2I, UIR };

static int tap_next(int s, int tms)
{
    switch (s) {
    case TLR: return tms ? TLR : RTI;
    case RTI: return tms ? SDS : RTI;
    case SDS: return tms ? SIS : CDR;
    case CDR: return tms ? E1D : SDR;
    case SDR: return tms ? E1D : SDR;
    case E1D: return tms ? UDR : PDR;
    case PDR: return tms ? E2D : PDR;
    case E2D: return tms ? UDR : SDR;
    case UDR: return tms ? SDS : RTI;
    case SIS: return tms ? TLR : CIR;
    case CIR: return tms ? E1I : SIR;
    case SIR: return tms ? E1I : SIR;
    case E1I: return tms ? UIR : PIR;
    case PIR: return tms ? E2I : PIR;
    case E2I: return tms ? UIR : SIR;
    default: return tms ? SDS : RTI; /* UIR */
    }
}

#define IR_LEN 6
#define IR_IDCODE 0x09u
#define IR_BYPASS 0x3Fu

struct tap {
    uint32_t idcode; /* 0: the device has no IDCODE (BYPASS at reset) */
    uint32_t ir, ir_shift;
    uint64_t dr_shift;
    int dr_len;
    /* configuration */
    uint8_t *cfg;    /* bits received through CFG_IN, one per byte */
    size_t ncfg, capcfg;
    int done, init, started, idle_after_start;
};

static int tap_cfg_valid(const struct tap *t)
{
    /* the sync word, MSB first, anywhere in the bit stream */
    const uint32_t sync = 0xAA995566u;
    uint32_t w = 0;
    for (size_t i = 0; i < t->ncfg; i++) {
        w = (w << 1) | t->cfg[i];
        if (i >= 31 && w == sync)
            return 1;
    }
    return 0;
}

struct chain {
    struct tap dev[4]; /* dev[0] nearest TDI */
    int n;
    int state;
    int stuck_tdo; /* -1 none, 0/1 stuck level */
    uint64_t tck;
};

static void tap_reset_ir(struct tap *t)
{
    t->ir = t->idcode ? IR_IDCODE : IR_BYPASS;
}

static int chain_tdo(const struct chain *c)
{
    if (c->stuck_tdo >= 0)
        return c->stuck_tdo;
    const struct tap *t = &c->dev[c->n - 1];
    if (c->state == SIR)
        return (int)(t->ir_shift & 1u);
    if (c->state == SDR)
        return (int)(t->dr_shift & 1u);
    return 1; /* TDO is high-Z outside the shift states: pulled up */
}

/* One TCK: TDO is what the chain drives before the rising edge; on the edge
 * every device samples TMS and its TDI. */
static int chain_clock(struct chain *c, int tms, int tdi)
{
    int tdo = chain_tdo(c);
    int in = tdi;
    for (int i = 0; i < c->n; i++) {
        struct tap *t = &c->dev[i];
        int out;
        if (c->state == SIR) {
            out = (int)(t->ir_shift & 1u);
            t->ir_shift = (t->ir_shift >> 1) | ((uint32_t)in << (IR_LEN - 1));
        } else if (c->state == SDR) {
            out = (int)(t->dr_shift & 1u);
            t->dr_shift = (t->dr_shift >> 1) | ((uint64_t)in << (t->dr_len - 1));
            if (t->ir == 0x05u) {
                if (t->ncfg == t->capcfg) {
                    t->capcfg = t->capcfg ? 2 * t->capcfg : 4096;
                    t->cfg = realloc(t->cfg, t->capcfg);
                }
                t->cfg[t->ncfg++] = (uint8_t)in;
            }
        } else {
            out = 1;
        }
        in = out;
    }
    int next = tap_next(c->state, tms);
    for (int i = 0; i < c->n; i++) {
        struct tap *t = &c->dev[i];
        if (next == TLR)
            tap_reset_ir(t);
        if (next == CIR)
            t->ir_shift = 0x01u | (t->init ? 0x10u : 0) | (t->done ? 0x20u : 0);
        if (next == UIR) {
            t->ir = t->ir_shift & 0x3Fu;
            if (t->ir == 0x0Bu) { /* JPROGRAM */
                t->ncfg = 0;
                t->done = 0;
                t->init = 1;
                t->started = 0;
            }
            if (t->ir == 0x0Cu) { /* JSTART */
                t->started = 1;
                t->idle_after_start = 0;
            }
        }
        if (c->state == RTI && t->started && ++t->idle_after_start == 16) {
            t->done = tap_cfg_valid(t);
            t->init = t->done;
        }
        if (next == CDR) {
            int idc = t->ir == IR_IDCODE && t->idcode;
            t->dr_len = idc ? 32 : 1;
            t->dr_shift = idc ? t->idcode : 0;
        }
    }
    c->state = next;
    c->tck++;
    return tdo;
}

/* ---- FTDI MPSSE model (the transport) ---- */

struct ftdi {
    struct chain *chain;
    uint8_t reply[1 << 16];
    size_t nreply, rpos;
    int tms_pin, tdi_pin;
    int pins_set, div_set, bad;
    size_t bytes_in, fail_after; /* write fails once bytes_in would pass it (0: never) */
    int seen_send_immediate;
    char err[128];
};

static void reply_byte(struct ftdi *f, uint8_t b)
{
    if (f->nreply < sizeof(f->reply))
        f->reply[f->nreply++] = b;
}

static size_t decode_one(struct ftdi *f, const uint8_t *p, size_t n)
{
    struct chain *c = f->chain;
    uint8_t op = p[0];
    switch (op) {
    case 0x8A: case 0x97: case 0x8D: case 0x85: return 1;
    case 0x87: f->seen_send_immediate = 1; return 1;
    case 0x80:
        if (n < 3)
            break;
        f->pins_set = p[2] == 0x0B;
        f->tms_pin = (p[1] >> 3) & 1;
        f->tdi_pin = (p[1] >> 1) & 1;
        return 3;
    case 0x86: f->div_set = 1; return n >= 3 ? 3 : 0;
    case 0x19: case 0x39: {
        if (n < 3)
            break;
        size_t len = (size_t)p[1] + ((size_t)p[2] << 8) + 1;
        if (n < 3 + len)
            break;
        for (size_t k = 0; k < len; k++) {
            uint8_t in = 0;
            for (int b = 0; b < 8; b++)
                in |= (uint8_t)(chain_clock(c, f->tms_pin, (p[3 + k] >> b) & 1) << b);
            if (op == 0x39)
                reply_byte(f, in);
        }
        return 3 + len;
    }
    case 0x1B: case 0x3B: {
        if (n < 3)
            break;
        int len = p[1] + 1;
        uint8_t in = 0;
        for (int b = 0; b < len; b++) {
            in >>= 1;
            in |= (uint8_t)(chain_clock(c, f->tms_pin, (p[2] >> b) & 1) << 7);
        }
        if (op == 0x3B)
            reply_byte(f, in);
        return 3;
    }
    case 0x4B: case 0x6B: {
        if (n < 3)
            break;
        int len = p[1] + 1;
        f->tdi_pin = (p[2] >> 7) & 1;
        uint8_t in = 0;
        for (int b = 0; b < len; b++) {
            f->tms_pin = (p[2] >> b) & 1;
            in >>= 1;
            in |= (uint8_t)(chain_clock(c, f->tms_pin, f->tdi_pin) << 7);
        }
        if (op == 0x6B)
            reply_byte(f, in);
        return 3;
    }
    default: break;
    }
    f->bad = 1;
    return 0;
}

static int ftdi_write(void *ctx, const uint8_t *buf, size_t n)
{
    struct ftdi *f = ctx;
    if (f->fail_after && f->bytes_in + n > f->fail_after) {
        snprintf(f->err, sizeof(f->err), "LIBUSB_ERROR_NO_DEVICE (the cable was unplugged)");
        return -ENODEV;
    }
    f->bytes_in += n;
    size_t pos = 0;
    while (pos < n) {
        size_t used = decode_one(f, buf + pos, n - pos);
        if (!used) {
            snprintf(f->err, sizeof(f->err), "bad MPSSE command 0x%02X", buf[pos]);
            return -EPROTO;
        }
        pos += used;
    }
    return 0;
}

static int ftdi_read(void *ctx, uint8_t *buf, size_t n)
{
    struct ftdi *f = ctx;
    if (f->nreply - f->rpos < n) {
        snprintf(f->err, sizeof(f->err), "timeout: %zu bytes asked, %zu there", n,
                 f->nreply - f->rpos);
        return -ETIMEDOUT;
    }
    memcpy(buf, f->reply + f->rpos, n);
    f->rpos += n;
    return 0;
}

static const char *ftdi_error(void *ctx)
{
    return ((struct ftdi *)ctx)->err;
}

struct rig {
    struct chain chain;
    struct ftdi ftdi;
    struct mpsse m;
    struct jtag j;
};

static void rig_open(struct rig *r, const uint32_t *ids, int n)
{
    memset(r, 0, sizeof(*r));
    r->chain.n = n;
    r->chain.stuck_tdo = -1;
    r->chain.state = RTI; /* not reset yet: the engine must reset */
    for (int i = 0; i < n; i++) {
        r->chain.dev[i].idcode = ids[i];
        r->chain.dev[i].init = 1;
        tap_reset_ir(&r->chain.dev[i]);
    }
    r->ftdi.chain = &r->chain;
    struct mpsse_transport t = {ftdi_write, ftdi_read, ftdi_error, &r->ftdi};
    CHECK_EQ_INT(mpsse_open(&r->m, &t, 6000000), 0);
    struct jtag_cable cable = mpsse_cable(&r->m);
    jtag_init(&r->j, &cable);
}

/* ---- tests ---- */

static void test_tms_paths(void)
{
    static const struct {
        enum jtag_state from, to;
        int len;
    } known[] = {{JTAG_TLR, JTAG_SHIFT_DR, 4}, {JTAG_TLR, JTAG_SHIFT_IR, 5},
                 {JTAG_RTI, JTAG_RTI, 0},      {JTAG_EXIT1_DR, JTAG_RTI, 2},
                 {JTAG_SHIFT_IR, JTAG_SHIFT_DR, 5}, {JTAG_PAUSE_DR, JTAG_SHIFT_DR, 2}};
    for (size_t i = 0; i < sizeof(known) / sizeof(known[0]); i++) {
        uint8_t tms;
        CHECK_EQ_INT(jtag_tms_path(known[i].from, known[i].to, &tms), known[i].len);
    }
    /* every path reaches its target in the model's own state table */
    int maxlen = 0;
    for (int a = 0; a < JTAG_NUM_STATES; a++)
        for (int b = 0; b < JTAG_NUM_STATES; b++) {
            uint8_t tms;
            int n = jtag_tms_path((enum jtag_state)a, (enum jtag_state)b, &tms);
            int s = a;
            for (int k = 0; k < n; k++)
                s = tap_next(s, (tms >> k) & 1);
            CHECK(n <= 8);
            maxlen = n > maxlen ? n : maxlen;
            CHECK_EQ_INT(s, b);
        }
    CHECK_EQ_INT(maxlen, 8); /* Select-IR-Scan to Exit2-DR */
}

static void test_setup_stream(void)
{
    struct rig r;
    uint32_t ids[] = {0x24001093u};
    rig_open(&r, ids, 1);
    CHECK(r.ftdi.pins_set);
    CHECK(r.ftdi.div_set);
    CHECK(!r.ftdi.bad);
    mpsse_close(&r.m);
}

static void test_chain_scan(void)
{
    struct rig r;
    uint32_t ids[] = {0x24001093u, 0x0141C093u, 0}; /* LX9 at TDI, a no-IDCODE part at TDO */
    rig_open(&r, ids, 3);
    uint32_t got[8];
    int n = 0;
    CHECK_EQ_INT(jtag_scan_chain(&r.j, got, 8, &n), 0);
    CHECK_EQ_INT(n, 3);
    CHECK_EQ_INT(got[0], 0);           /* nearest TDO first */
    CHECK_EQ_INT(got[1], 0x0141C093u);
    CHECK_EQ_INT(got[2], 0x24001093u);
    CHECK(r.ftdi.seen_send_immediate);
    CHECK_EQ_INT(r.chain.state, RTI);
    CHECK(jtag_part_by_idcode(0x24001093u) && jtag_part_by_idcode(0x34001093u));
    CHECK(strcmp(jtag_part_by_idcode(0x24001093u)->name, "XC6SLX9") == 0);
    CHECK(jtag_part_by_idcode(0x12345679u) == NULL);
    mpsse_close(&r.m);
}

static void test_ir_dr_scans(void)
{
    struct rig r;
    uint32_t ids[] = {0x24001093u, 0x0141C093u};
    rig_open(&r, ids, 2);
    CHECK_EQ_INT(jtag_reset(&r.j), 0);
    CHECK_EQ_INT(r.chain.state, TLR);
    /* device 1 (nearest TDO) gets BYPASS, device 0 IDCODE: bits go in LSB
     * first and the first 6 end in the device nearest TDO */
    uint16_t ir = (uint16_t)(IR_BYPASS | (IR_IDCODE << 6));
    uint8_t in[2] = {(uint8_t)ir, (uint8_t)(ir >> 8)}, out[2] = {0, 0};
    CHECK_EQ_INT(jtag_scan_ir(&r.j, in, out, 12, JTAG_RTI), 0);
    CHECK_EQ_INT(out[0] | (out[1] << 8), 0x451); /* both capture 010001: INIT, ...01 */
    CHECK_EQ_INT(r.chain.dev[1].ir, IR_BYPASS);
    CHECK_EQ_INT(r.chain.dev[0].ir, IR_IDCODE);
    uint8_t din[5] = {0}, dout[5] = {0};
    CHECK_EQ_INT(jtag_scan_dr(&r.j, din, dout, 33, JTAG_PAUSE_DR), 0);
    uint64_t v = 0;
    for (int i = 0; i < 5; i++)
        v |= (uint64_t)dout[i] << (8 * i);
    CHECK_EQ_INT(v & 1u, 0);                        /* the BYPASS bit */
    CHECK_EQ_INT((v >> 1) & 0xFFFFFFFFu, 0x24001093u); /* then device 0's IDCODE */
    CHECK_EQ_INT(r.chain.state, PDR);
    CHECK_EQ_INT(jtag_idle(&r.j, 100), 0);
    CHECK_EQ_INT(r.chain.state, RTI);
    mpsse_close(&r.m);
}

static void test_long_scan_cost(void)
{
    struct rig r;
    uint32_t ids[] = {0x24001093u};
    rig_open(&r, ids, 1);
    CHECK_EQ_INT(jtag_reset(&r.j), 0);
    enum { BITS = 8 * 100000 };
    uint8_t *buf = calloc(BITS / 8, 1);
    uint64_t before = r.m.bytes_out, tck0 = r.chain.tck;
    CHECK_EQ_INT(jtag_scan_dr(&r.j, buf, NULL, BITS, JTAG_RTI), 0);
    struct jtag_cable cab = mpsse_cable(&r.m);
    CHECK_EQ_INT(cab.flush(cab.ctx), 0);
    double per_bit = (double)(r.m.bytes_out - before) / (double)(r.chain.tck - tck0);
    CHECK(per_bit < 0.13); /* a byte per 8 TCK, plus a header per 64 KiB */
    CHECK(r.chain.tck - tck0 >= BITS);
    free(buf);
    mpsse_close(&r.m);
}

static void test_stuck_tdo(void)
{
    for (int level = 0; level < 2; level++) {
        struct rig r;
        uint32_t ids[] = {0x24001093u};
        rig_open(&r, ids, 1);
        r.chain.stuck_tdo = level;
        uint32_t got[4];
        int n = -1;
        CHECK_EQ_INT(jtag_scan_chain(&r.j, got, 4, &n), -EIO);
        CHECK(strstr(r.j.err, level ? "all ones" : "all zeros") != NULL);
        mpsse_close(&r.m);
    }
}

static void test_cable_vanishes(void)
{
    struct rig r;
    uint32_t ids[] = {0x24001093u};
    rig_open(&r, ids, 1);
    r.ftdi.fail_after = r.ftdi.bytes_in + 20;
    uint32_t got[4];
    int n = 0;
    int rc = jtag_scan_chain(&r.j, got, 4, &n);
    CHECK(rc == -ENODEV);
    CHECK(strstr(r.j.err, "unplugged") != NULL);
    CHECK(strstr(r.j.err, "JTAG") != NULL);
    /* the state is unknown now: scans refuse until a reset */
    uint8_t b = 0;
    CHECK_EQ_INT(jtag_scan_dr(&r.j, &b, NULL, 1, JTAG_RTI), -EINVAL);
    mpsse_close(&r.m);
}

static void rig_close(struct rig *r)
{
    for (int i = 0; i < r->chain.n; i++)
        free(r->chain.dev[i].cfg);
    mpsse_close(&r->m);
}

static void check_received(const struct tap *t, const uint8_t *bits, size_t len, size_t lead)
{
    CHECK_EQ_INT(t->ncfg, len * 8 + lead);
    int same = t->ncfg == len * 8 + lead;
    for (size_t i = 0; same && i < lead; i++)
        same = t->cfg[i] == 0;
    for (size_t i = 0; same && i < len * 8; i++)
        same = t->cfg[lead + i] == ((bits[i / 8] >> (7 - i % 8)) & 1);
    CHECK(same);
}

static void test_xilinx_program(void)
{
    uint8_t bits[300];
    for (size_t i = 0; i < sizeof(bits); i++)
        bits[i] = (uint8_t)(i * 37 + 11);
    memcpy(bits + 16, "\xAA\x99\x55\x66", 4);
    for (int pos = 0; pos < 3; pos++) {
        struct rig r;
        uint32_t ids[] = {0x0141C093u, 0x24001093u, 0x01414093u}; /* dev[0] nearest TDI */
        rig_open(&r, ids, 3);
        uint8_t st = 0;
        CHECK_EQ_INT(jtag_xilinx_program(&r.j, pos, 3, bits, sizeof(bits), &st), 0);
        CHECK_EQ_INT(st & 0x33, 0x31); /* DONE, INIT, ...01 */
        /* device `pos` counted from TDO is dev[2 - pos]; the BYPASS devices
         * between TDI and it put one zero bit each in front */
        const struct tap *t = &r.chain.dev[2 - pos];
        check_received(t, bits, sizeof(bits), (size_t)(2 - pos));
        CHECK(t->done);
        for (int k = 0; k < 3; k++)
            if (k != 2 - pos)
                CHECK_EQ_INT(r.chain.dev[k].ncfg, 0);
        rig_close(&r);
    }
}

static void test_xilinx_bad_bitstream(void)
{
    struct rig r;
    uint32_t ids[] = {0x24001093u};
    rig_open(&r, ids, 1);
    uint8_t bits[64];
    memset(bits, 0x5A, sizeof(bits)); /* no sync word */
    uint8_t st = 0xFF;
    CHECK_EQ_INT(jtag_xilinx_program(&r.j, 0, 1, bits, sizeof(bits), &st), -EIO);
    CHECK_EQ_INT(st & 0x30, 0x00);
    CHECK(strstr(r.j.err, "did not assert DONE") && strstr(r.j.err, "CRC error"));
    CHECK_EQ_INT(jtag_xilinx_program(&r.j, 1, 1, bits, sizeof(bits), &st), -EINVAL);
    rig_close(&r);
}

/* ---- the GPIO cable on a model of the wire ---- */

struct wire {
    struct chain *chain;
    int level[JTAG_GPIO_N];
    int fail_role, fail_after; /* set() of fail_role fails after that many calls */
    int calls;
    uint64_t tdo_reads_while_low;
};

static int wire_set(void *ctx, int role, int level)
{
    struct wire *w = ctx;
    if (role == w->fail_role && ++w->calls > w->fail_after)
        return -EIO;
    if (role == JTAG_GPIO_TCK && level && !w->level[JTAG_GPIO_TCK])
        chain_clock(w->chain, w->level[JTAG_GPIO_TMS], w->level[JTAG_GPIO_TDI]); /* rising */
    w->level[role] = level;
    return 0;
}

static int wire_get(void *ctx, int role, int *level)
{
    struct wire *w = ctx;
    if (role != JTAG_GPIO_TDO)
        return -EINVAL;
    w->tdo_reads_while_low += !w->level[JTAG_GPIO_TCK];
    *level = chain_tdo(w->chain);
    return 0;
}

static void wire_close(void *ctx)
{
    (void)ctx;
}

static void test_gpio_cable(void)
{
    struct chain c;
    memset(&c, 0, sizeof(c));
    uint32_t ids[] = {0x0141C093u, 0x24001093u};
    c.n = 2;
    c.stuck_tdo = -1;
    c.state = RTI;
    for (int i = 0; i < 2; i++) {
        c.dev[i].idcode = ids[i];
        c.dev[i].init = 1;
        tap_reset_ir(&c.dev[i]);
    }
    struct wire w = {&c, {0, 1, 0, 0}, -1, 0, 0, 0};
    struct jtag_gpio_lines lines = {wire_set, wire_get, wire_close, &w};
    struct jtag_gpio g;
    jtag_gpio_init(&g, &lines);
    struct jtag_cable cab = jtag_gpio_cable(&g);
    struct jtag j;
    jtag_init(&j, &cab);
    uint32_t got[4];
    int n = 0;
    CHECK_EQ_INT(jtag_scan_chain(&j, got, 4, &n), 0);
    CHECK_EQ_INT(n, 2);
    CHECK_EQ_INT(got[0], 0x24001093u);
    CHECK_EQ_INT(got[1], 0x0141C093u);
    CHECK_EQ_INT(g.tck, c.tck); /* one rising edge per bit, no more */
    CHECK(w.tdo_reads_while_low > 0);
    uint8_t bits[40];
    memset(bits, 0x3C, sizeof(bits));
    memcpy(bits + 8, "\xAA\x99\x55\x66", 4);
    uint8_t st = 0;
    CHECK_EQ_INT(jtag_xilinx_program(&j, 0, 2, bits, sizeof(bits), &st), 0);
    check_received(&c.dev[1], bits, sizeof(bits), 1);
    CHECK(c.dev[1].done);
    /* a line that stops working: an error naming it, no hang */
    w.fail_role = JTAG_GPIO_TCK;
    w.fail_after = w.calls = 0;
    CHECK_EQ_INT(jtag_scan_chain(&j, got, 4, &n), -EIO);
    CHECK(strstr(j.err, "GPIO set of line TCK failed") != NULL);
    for (int i = 0; i < 2; i++)
        free(c.dev[i].cfg);
}

int main(void)
{
    RUN(test_tms_paths);
    RUN(test_setup_stream);
    RUN(test_chain_scan);
    RUN(test_ir_dr_scans);
    RUN(test_long_scan_cost);
    RUN(test_stuck_tdo);
    RUN(test_cable_vanishes);
    RUN(test_xilinx_program);
    RUN(test_xilinx_bad_bitstream);
    RUN(test_gpio_cable);
    return check_summary();
}
