/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of the Pluto-P drivers' logic (host/driver/pluto) against the
 * formulas of spec/pluto.md and a register-level model of the Pluto EPP
 * front end and its passive-serial configuration (tests/unit/epp/fakes.c):
 * encodings, decodings, EPP cycle lists and counts per servo period,
 * communication errors, the firmware upload on the control/data lines.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <unistd.h>
#include <stdlib.h>
#include <string.h>

#include "../check.h"
#include "../epp/fakes.h"
#include "pluto_drivers.h"

static char logbuf[8192];
static size_t loglen;
static void cap_log(void *ctx, int level, const char *fmt, ...)
{
    (void)ctx;
    va_list ap;
    va_start(ap, fmt);
    if (loglen < sizeof(logbuf) - 256) {
        loglen += (size_t)snprintf(logbuf + loglen, sizeof(logbuf) - loglen, "%c:", '0' + level);
        loglen += (size_t)vsnprintf(logbuf + loglen, sizeof(logbuf) - loglen, fmt, ap);
    }
    va_end(ap);
}
static void log_clear(void)
{
    loglen = 0;
    logbuf[0] = 0;
}

static struct periph P;
static struct pcport PC;
static struct fake_raw FR;
static epp_port_t PORT;

static void open_raw_pluto(int wide)
{
    char err[200];
    periph_init(&P, PERIPH_PLUTO);
    pcport_init(&PC, &P);
    memset(&FR, 0, sizeof(FR));
    FR.pc = &PC;
    FR.base = 0x378;
    FR.base_hi = 0x778;
    struct epp_raw_io io = fake_raw_io(&FR);
    CHECK_EQ_INT(epp_raw_open(&PORT, &io, 0x378, 0x778, wide, err, sizeof(err)), 0);
}

static void clear_traces(void)
{
    PC.log_len = 0;
    PC.log[0] = 0;
    P.trace_len = 0;
    P.trace[0] = 0;
}

/* ---- count extension ---------------------------------------------------- */

static uint64_t rng = 88172645463325252ull;
static uint64_t xr(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static void test_extend(void)
{
    /* spec examples: forward and backward across the wrap */
    CHECK_EQ_INT(pluto_extend(16380, 3, 14), 16387);
    CHECK_EQ_INT(pluto_extend(3, 16380, 14), -4);
    CHECK_EQ_INT(pluto_extend(100, 16380, 14), -4);
    CHECK_EQ_INT(pluto_extend(-4, 100, 14), 100);
    CHECK_EQ_INT(pluto_extend(0, 0x1FFFFF, 21), -1);
    CHECK_EQ_INT(pluto_extend(5 * 16384 + 8000, 200, 14), 5 * 16384 + 200);
    CHECK_EQ_INT(pluto_extend(5 * 16384 + 16000, 200, 14), 6 * 16384 + 200);
    /* property: congruent to low, within half a wrap of old */
    for (int bits = 14; bits <= 21; bits += 7) {
        int64_t half = (int64_t)1 << (bits - 1);
        for (int i = 0; i < 20000; i++) {
            int64_t old = (int64_t)(xr() % 2000000) - 1000000;
            int64_t delta = (int64_t)(xr() % (uint64_t)(2 * half - 1)) - (half - 1);
            int64_t truth = old + delta;
            uint32_t low = (uint32_t)(truth & ((1 << bits) - 1));
            int64_t got = pluto_extend(old, low, bits);
            if (got != truth) {
                CHECK_EQ_INT(got, truth);
                break;
            }
        }
    }
}

/* ---- pluto_servo -------------------------------------------------------- */

static struct pluto_servo S;
static hal_s32_t e_count[4];
static hal_float_t e_pos[4], e_vel[4], pwm_val[4];
static hal_bit_t e_reset[4], e_idx[4], pwm_en[4], dout[20], din[20], din_not[20];

static void servo_setup(epp_port_t *port)
{
    memset(&S, 0, sizeof(S));
    for (int i = 0; i < 4; i++) {
        S.enc_count[i] = &e_count[i];
        S.enc_position[i] = &e_pos[i];
        S.enc_velocity[i] = &e_vel[i];
        S.enc_reset[i] = &e_reset[i];
        S.enc_index_enable[i] = &e_idx[i];
        S.pwm_value[i] = &pwm_val[i];
        S.pwm_enable[i] = &pwm_en[i];
        e_reset[i] = e_idx[i] = pwm_en[i] = 0;
        pwm_val[i] = 0;
    }
    for (int i = 0; i < 20; i++) {
        S.dout[i] = &dout[i];
        S.din[i] = &din[i];
        S.din_not[i] = &din_not[i];
        dout[i] = 0;
    }
    pluto_servo_defaults(&S);
    S.port = port;
    S.watchdog = 1;
    S.log.fn = cap_log;
}

static void test_servo_defaults(void)
{
    servo_setup(NULL);
    for (int i = 0; i < 4; i++) {
        CHECK(S.enc_scale[i] == 1.0 && S.pwm_scale[i] == 1.0 && S.pwm_max_dc[i] == 1.0);
        CHECK(S.pwm_min_dc[i] == 0.0 && S.pwm_offset[i] == 0.0 && !S.pwm_pwmdir[i]);
    }
    CHECK(!S.z_polarity && !S.is_pdm && S.communication_error == 0);
}

static void test_servo_pwm_word(void)
{
    servo_setup(NULL);
    pwm_en[0] = 1;
    struct {
        double value, scale, offset, maxdc, mindc;
        int pwmdir;
        unsigned want;
    } c[] = {
        {0.5, 1, 0, 1, 0, 0, 1023},               /* 0.5 * 2047 = 1023.5 truncated */
        {-0.5, 1, 0, 1, 0, 0, 0x8000 | 1023},     /* up/down: sign bit 15 */
        {-0.5, 1, 0, 1, 0, 1, 0x2000 | 1023},     /* pwm+dir: DN (bit 13) as DIR */
        {2.0, 1, 0, 1, 0, 0, 2047},               /* clamped to max-dc */
        {-7.0, 1, 0, 1, 0, 0, 0x8000 | 2047},
        {0.9, 1, 0, 0.5, 0, 0, 1023},             /* max-dc 0.5 */
        {0.001, 1, 0, 1, 0.1, 0, 204},            /* raised to min-dc: 204.7 */
        {-0.001, 1, 0, 1, 0.1, 0, 0x8000 | 204},
        {0.0, 1, 0, 1, 0.1, 0, 0},                /* exact 0 stays 0 */
        {5.0, 10, 0, 1, 0, 0, 1023},              /* scale */
        {0.5, -1, 0, 1, 0, 0, 0x8000 | 1023},     /* negative scale */
        {0.0, 1, 0.25, 1, 0, 0, 511},             /* offset: 511.75 */
        {1.0, 0, 0, 1, 0, 0, 2047},               /* scale 0: +inf clamps */
        {NAN, 1, 0, 1, 0, 0, 0},                  /* NaN value: off */
    };
    for (size_t k = 0; k < sizeof(c) / sizeof(c[0]); k++) {
        pwm_val[0] = c[k].value;
        S.pwm_scale[0] = c[k].scale;
        S.pwm_offset[0] = c[k].offset;
        S.pwm_max_dc[0] = c[k].maxdc;
        S.pwm_min_dc[0] = c[k].mindc;
        S.pwm_pwmdir[0] = c[k].pwmdir;
        unsigned got = pluto_servo_pwm_word(&S, 0);
        if (got != c[k].want)
            fprintf(stderr, "case %zu: got 0x%04x want 0x%04x\n", k, got, c[k].want);
        CHECK_EQ_INT(got, c[k].want);
    }
    /* parameters are rewritten into range */
    S.pwm_scale[0] = 1;
    S.pwm_offset[0] = 0;
    S.pwm_max_dc[0] = 1.5;
    S.pwm_min_dc[0] = -0.2;
    pluto_servo_pwm_word(&S, 0);
    CHECK(S.pwm_max_dc[0] == 1.0 && S.pwm_min_dc[0] == 0.0);
    S.pwm_max_dc[0] = 0.3;
    S.pwm_min_dc[0] = 0.6;
    pluto_servo_pwm_word(&S, 0);
    CHECK(S.pwm_max_dc[0] == 0.3 && S.pwm_min_dc[0] == 0.3);
    S.pwm_max_dc[0] = -1;
    pluto_servo_pwm_word(&S, 0);
    CHECK(S.pwm_max_dc[0] == 0.0);
    S.pwm_max_dc[0] = 1;
    S.pwm_min_dc[0] = 0;
    /* shared outputs: dout.10/11 XOR into UP0/DN0; PDM bit; enable=0 */
    pwm_val[0] = -0.5;
    S.pwm_pwmdir[0] = 1;
    S.dout_invert[11] = 1; /* DIR high for positive */
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 0), 1023);
    pwm_val[0] = 0.5;
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 0), 0x2000 | 1023);
    S.dout_invert[11] = 0;
    dout[10] = 1;
    S.is_pdm = 1;
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 0), 0x4000 | 0x1000 | 1023);
    pwm_en[0] = 0;
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 0), 0);
    /* channel 3 uses dout.16/17 */
    pwm_en[3] = 1;
    S.is_pdm = 0;
    dout[16] = 1;
    dout[17] = 1;
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 3), 0x3000);
}

static void test_servo_control_word(void)
{
    servo_setup(NULL);
    S.watchdog = 0;
    CHECK_EQ_INT(pluto_servo_control_word(&S), 0);
    dout[0] = dout[3] = dout[9] = 1;
    S.dout_invert[3] = S.dout_invert[4] = 1;
    S.watchdog = 1;
    CHECK_EQ_INT(pluto_servo_control_word(&S), 0x4000 | 0x200 | 0x10 | 0x1);
    S.z_polarity = 1;
    S.test_encoder = 1;
    CHECK_EQ_INT(pluto_servo_control_word(&S), 0x8000 | 0x4000 | 0x2000 | 0x200 | 0x10 | 0x1);
    dout[18] = dout[19] = 1; /* no effect */
    CHECK_EQ_INT(pluto_servo_control_word(&S), 0x8000 | 0x4000 | 0x2000 | 0x200 | 0x10 | 0x1);
}

static void test_servo_write_cycles(void)
{
    for (int wide = 0; wide < 2; wide++) {
        open_raw_pluto(wide);
        servo_setup(&PORT);
        for (int i = 0; i < 4; i++) {
            pwm_en[i] = 1;
            pwm_val[i] = 0.25 * (i + 1) * (i % 2 ? -1 : 1);
        }
        dout[1] = 1;
        clear_traces();
        epp_counters_reset(&PORT);
        pluto_servo_write(&S, 1000000);
        uint16_t want[5] = {511, 0x8000 | 1023, 1535, 0x8000 | 2047, 0x4002};
        for (int r = 0; r < 5; r++) {
            CHECK_EQ_INT(P.wreg[r], want[r]);
            CHECK_EQ_INT(P.wcommits[r], 1);
        }
        CHECK_EQ_STR(P.trace, "A(00) W(ff) W(01) W(ff) W(83) W(ff) W(05) W(ff) W(87) W(02) "
                              "W(40) ");
        if (wide)
            CHECK_EQ_STR(PC.log, "outb(00,+3) outl(83ff01ff,+4) outl(87ff05ff,+4) "
                                 "outw(4002,+4) ");
        CHECK_EQ_INT(PORT.count.addr_cycles, 1);
        CHECK_EQ_INT(PORT.count.data_cycles, 10);
        CHECK_EQ_INT(PORT.count.port_ios, wide ? 4 : 11);
        epp_port_close(&PORT);
    }
}

static void set_enc(int ch, uint32_t count, uint32_t latched, int indexed)
{
    P.rreg[ch] = (count & 0x3FFF) | (latched & 0x3FFF) << 14 | (indexed ? 1u << 28 : 0);
}

static void test_servo_read(void)
{
    open_raw_pluto(1);
    servo_setup(&PORT);
    S.enc_scale[0] = 4.0;
    set_enc(0, 100, 0, 0);
    set_enc(1, 16000, 0, 0);
    P.rreg[4] = 0xA5A5A;
    clear_traces();
    epp_counters_reset(&PORT);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_STR(PC.log, "outb(00,+3) inl(+4) inb(+1) inl(+4) inl(+4) inl(+4) inl(+4) ");
    CHECK_EQ_INT(PORT.count.addr_cycles, 1);
    CHECK_EQ_INT(PORT.count.data_cycles, 20);
    CHECK_EQ_INT(e_count[0], 100);
    CHECK_NEAR(e_pos[0], 25.0, 1e-12);
    CHECK_NEAR(e_vel[0], 100 / 4.0 / 0.001, 1e-6);
    CHECK_EQ_INT(e_count[1], -384); /* 16000 is nearer to -384 than to +16000 */
    CHECK_EQ_INT(S.debug_0, 100);
    CHECK_EQ_INT(S.debug_1, 100);
    for (int i = 0; i < 20; i++) {
        CHECK_EQ_INT(din[i], (0xA5A5A >> i) & 1);
        CHECK_EQ_INT(din_not[i], !((0xA5A5A >> i) & 1));
    }
    /* wrap backwards over 0 */
    set_enc(0, 16380, 0, 0);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(e_count[0], -4);
    CHECK_NEAR(e_vel[0], -104 / 4.0 / 0.001, 1e-6);
    /* 1000 servo periods of +7000 counts: 7,000,000 counts tracked */
    int64_t truth = -4;
    for (int k = 0; k < 1000; k++) {
        truth += 7000;
        set_enc(0, (uint32_t)(truth & 0x3FFF), 0, 0);
        pluto_servo_read(&S, 1000000);
    }
    CHECK_EQ_INT(e_count[0], truth);
    /* index with index-enable: reset to the latched count, pin cleared */
    e_idx[2] = 1;
    set_enc(2, 500, 0, 0);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(e_count[2], 500);
    CHECK_EQ_INT(e_idx[2], 1);
    set_enc(2, 900, 700, 1);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(e_idx[2], 0);
    CHECK_EQ_INT(e_count[2], 200);
    CHECK_EQ_INT(P.index_reads[2], 1);
    /* an index while index-enable is false is discarded */
    set_enc(2, 1000, 950, 1);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(e_count[2], 300);
    /* latched count across a wrap: index at 16383 seen when the count is 5 */
    e_idx[3] = 1;
    set_enc(3, 16000, 0, 0);
    pluto_servo_read(&S, 1000000); /* -384 */
    set_enc(3, 5, 16383, 1);
    pluto_servo_read(&S, 1000000); /* count 16389-16384... = 5, index = -1 */
    CHECK_EQ_INT(e_count[3], 6);
    /* reset pin: count 0 and velocity 0 */
    e_reset[0] = 1;
    set_enc(0, (uint32_t)((truth + 50) & 0x3FFF), 0, 0);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(e_count[0], 0);
    CHECK(e_vel[0] == 0.0);
    e_reset[0] = 0;
    set_enc(0, (uint32_t)((truth + 80) & 0x3FFF), 0, 0);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(e_count[0], 30);
    epp_port_close(&PORT);
}

static void test_servo_comm_error(void)
{
    open_raw_pluto(1);
    servo_setup(&PORT);
    set_enc(0, 10, 0, 0);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(e_count[0], 10);
    P.stall = 1;
    set_enc(0, 20, 0, 0);
    clear_traces();
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(S.communication_error, 1);
    CHECK_EQ_STR(PC.log, "outb(00,+3) inl(+4) inb(+1) inb(+1) outb(79,+1) outb(78,+1) ");
    CHECK_EQ_INT(e_count[0], 10); /* frozen */
    clear_traces();
    pwm_en[0] = 1;
    pwm_val[0] = 0.5;
    pluto_servo_write(&S, 1000000);
    CHECK_EQ_STR(PC.log, ""); /* write skipped entirely */
    P.stall = 0;
    pluto_servo_read(&S, 1000000); /* still in error: first read only */
    CHECK_EQ_STR(PC.log, "outb(00,+3) inl(+4) inb(+1) ");
    CHECK_EQ_INT(S.communication_error, 1);
    CHECK_EQ_INT(e_count[0], 10);
    /* the user clears it: traffic resumes, the watchdog is petted again */
    S.communication_error = 0;
    pluto_servo_write(&S, 1000000);
    CHECK_EQ_INT(P.wreg[4] & 0x4000, 0x4000);
    CHECK_EQ_INT(P.wreg[0], 1023);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(e_count[0], 20);
    epp_port_close(&PORT);
}

static void test_servo_batched_counts(void)
{
    periph_init(&P, PERIPH_PLUTO);
    pcport_init(&PC, &P);
    fake_batch_open(&PORT, &PC, 1);
    servo_setup(&PORT);
    set_enc(1, 77, 0, 0);
    P.rreg[4] = 0x3;
    /* 10 servo periods: one round trip per function call */
    fake_batch_executes = 0;
    epp_counters_reset(&PORT);
    for (int k = 0; k < 10; k++) {
        pluto_servo_read(&S, 1000000);
        pluto_servo_write(&S, 1000000);
    }
    CHECK_EQ_INT(fake_batch_executes, 20);
    CHECK_EQ_INT(PORT.count.flushes, 20);
    CHECK_EQ_INT(PORT.count.addr_cycles, 20);
    CHECK_EQ_INT(PORT.count.data_cycles, 10 * (20 + 10));
    CHECK_EQ_INT(PORT.count.reg_accesses, 10); /* one status read per read */
    CHECK_EQ_INT(e_count[1], 77);
    CHECK_EQ_INT(din[0], 1);
    CHECK_EQ_INT(din[2], 0);
    /* a timeout on a batching port: counted, cleared, nothing decoded */
    P.stall = 1;
    set_enc(1, 99, 0, 0);
    pluto_servo_read(&S, 1000000);
    CHECK_EQ_INT(S.communication_error, 1);
    CHECK_EQ_INT(e_count[1], 77);
    CHECK_EQ_INT(PC.timeout, 0);
    epp_port_close(&PORT);
}

/* ---- pluto_step --------------------------------------------------------- */

static struct pluto_step T;
static hal_float_t s_cmd[4], s_vfb[4], s_pfb[4];
static hal_s32_t s_counts[4];
static hal_bit_t s_en[4], s_reset[4], s_dout[14], s_din[16], s_din_not[16];

static void step_setup(epp_port_t *port)
{
    memset(&T, 0, sizeof(T));
    for (int i = 0; i < 4; i++) {
        T.position_cmd[i] = &s_cmd[i];
        T.velocity_fb[i] = &s_vfb[i];
        T.position_fb[i] = &s_pfb[i];
        T.counts[i] = &s_counts[i];
        T.enable[i] = &s_en[i];
        T.reset[i] = &s_reset[i];
        s_cmd[i] = s_pfb[i] = 0;
        s_en[i] = s_reset[i] = 0;
    }
    for (int i = 0; i < 14; i++) {
        T.dout[i] = &s_dout[i];
        s_dout[i] = 0;
    }
    for (int i = 0; i < 16; i++) {
        T.din[i] = &s_din[i];
        T.din_not[i] = &s_din_not[i];
    }
    pluto_step_defaults(&T);
    T.port = port;
    T.log.fn = cap_log;
}

static void test_step_defaults_and_words(void)
{
    step_setup(NULL);
    CHECK(T.debug_2 == 0.5 && T.debug_3 == 2.0 && T.scale[0] == 1.0 && T.maxvel[3] == 0.0);
    CHECK_EQ_INT(pluto_step_ticks(0), 0);
    CHECK_EQ_INT(pluto_step_ticks(1599), 0);
    CHECK_EQ_INT(pluto_step_ticks(1600), 1);
    CHECK_EQ_INT(pluto_step_ticks(3199), 1);
    CHECK_EQ_INT(pluto_step_ticks(49600), 31);
    CHECK_EQ_INT(pluto_step_ticks(51199), 31);
    CHECK_EQ_INT(pluto_step_ticks(4000000000u), 31);
    T.steplen = 5000;
    T.dirtime = 20000;
    T.step_polarity = 1;
    CHECK_EQ_INT(pluto_step_timing_word(&T), 0x8000 | 12 << 8 | 3);
    s_dout[0] = s_dout[13] = 1;
    T.dout_invert[13] = T.dout_invert[5] = 1;
    T.watchdog = 0;
    CHECK_EQ_INT(pluto_step_dout_word(&T), 0x0021);
    T.watchdog = 1;
    CHECK_EQ_INT(pluto_step_dout_word(&T), 0x4021);
}

/* spec §6.2 for one channel, written out for the test */
static int ref_rate(double cmd, double old_cmd, double fb, double old_v, double T_s, double scale,
                    double fmax, int speedrange, double *v_out)
{
    double v = (cmd - old_cmd) - 0.5 * (fb + old_v * T_s - cmd) / T_s;
    v += v > 0 ? 0.5 / fabs(scale) : v < 0 ? -0.5 / fabs(scale) : 0;
    *v_out = v;
    double m = fmax / fabs(scale);
    v = v > m ? m : v < -m ? -m : v;
    double r = v * scale * 2048 * 1.6e-6 / (1 << speedrange);
    r = r > 1024 ? 1024 : r < -1024 ? -1024 : r;
    return (int)r;
}

static void test_step_write(void)
{
    open_raw_pluto(1);
    P.pluto_step = 1;
    step_setup(&PORT);
    T.watchdog = 1;
    for (int i = 0; i < 4; i++) {
        T.scale[i] = 1000.0 * (i + 1);
        s_en[i] = 1;
        s_cmd[i] = 0.01 * (i % 2 ? -1 : 1);
    }
    s_en[3] = 0;
    clear_traces();
    epp_counters_reset(&PORT);
    log_clear();
    pluto_step_write(&T, 1000000);
    double v;
    int want0 = ref_rate(0.01, 0, 0, 0, 1e-3, 1000, 312500, 0, &v);
    CHECK_EQ_INT(want0, 16);
    CHECK_EQ_INT(P.wreg[0], want0);
    CHECK_EQ_INT(T.debug_1, want0);
    int want1 = ref_rate(-0.01, 0, 0, 0, 1e-3, 2000, 312500, 0, &v);
    CHECK_EQ_INT((int16_t)P.wreg[1], want1);
    CHECK_EQ_INT(P.wreg[3], 0); /* disabled */
    CHECK_EQ_INT(P.wreg[4], 0x4000);
    CHECK_EQ_INT(P.wreg[5], 0);
    CHECK_EQ_STR(PC.log, "outb(00,+3) outw(0010,+4) outw(ffe0,+4) outw(0031,+4) outw(0000,+4) "
                         "outw(4000,+4) outw(0000,+4) ");
    CHECK_EQ_INT(PORT.count.addr_cycles, 1);
    CHECK_EQ_INT(PORT.count.data_cycles, 12);
    CHECK_EQ_STR(logbuf, "");
    /* second period: feedback followed the command */
    s_pfb[0] = 0.01;
    s_cmd[0] = 0.02;
    double v0 = T.old_velocity_cmd[0];
    pluto_step_write(&T, 1000000);
    CHECK_EQ_INT(P.wreg[0], ref_rate(0.02, 0.01, 0.01, v0, 1e-3, 1000, 312500, 0, &v));
    /* top rate: clamped to 1024 (0.5 step per tick) */
    s_cmd[0] = 1000;
    pluto_step_write(&T, 1000000);
    CHECK_EQ_INT(P.wreg[0], 1024);
    s_cmd[0] = -1000;
    pluto_step_write(&T, 1000000);
    CHECK_EQ_INT((int16_t)P.wreg[0], -1024);
    epp_port_close(&PORT);
}

static void test_step_limits_and_messages(void)
{
    open_raw_pluto(1);
    P.pluto_step = 1;
    step_setup(&PORT);
    T.watchdog = 0;
    log_clear();
    T.steplen = 60000;
    T.dirtime = 100000;
    pluto_step_write(&T, 1000000);
    CHECK_EQ_STR(logbuf, "1:Requested step length 60000ns decreased to 49600ns due to hardware "
                         "limitations\n1:Requested direction change time 100000ns decreased to "
                         "49600ns due to hardware limitations\n");
    CHECK_EQ_INT(T.steplen, 49600);
    CHECK_EQ_INT(T.dirtime, 49600);
    CHECK_EQ_INT(P.wreg[5], 31 | 31 << 8); /* as coded (spec §12) */
    log_clear();
    pluto_step_write(&T, 1000000);
    CHECK_EQ_STR(logbuf, "");
    /* maxvel above what steplen/stepspace allow: one message, clamped */
    T.steplen = 3200;   /* 2 ticks */
    T.stepspace = 4800; /* 3 ticks: fmax = 625000/7 */
    T.scale[0] = 100;
    T.maxvel[0] = -2000; /* negative: made positive */
    s_en[0] = 1;
    log_clear();
    pluto_step_write(&T, 1000000);
    CHECK_EQ_STR(logbuf, "1:Requested step rate 200000Hz decreased to 89285Hz due to hardware "
                         "or timing limitations\n");
    CHECK_NEAR(T.maxvel[0], 625000.0 / 7 / 100, 1e-9);
    T.maxvel[0] = 5000;
    log_clear();
    pluto_step_write(&T, 1000000);
    CHECK_EQ_STR(logbuf, ""); /* one-time */
    /* command far away: rate clamped to maxvel */
    T.maxvel[0] = 100; /* 10000 steps/s */
    s_cmd[0] = 50;
    pluto_step_write(&T, 1000000);
    CHECK_EQ_INT(P.wreg[0], (int)(100 * 100 * 2048 * 1.6e-6));
    /* speedrange divides the rate; with 2 + steplen + stepspace < 2^(n+1)
     * ticks LinuxCNC's second fmax limit assigns 1.6e-6 * 2^(n+1) (spec §12,
     * as coded): the rate collapses to 0 */
    T.speedrange = 2;
    pluto_step_write(&T, 1000000);
    CHECK_EQ_INT(P.wreg[0], 0);
    T.stepspace = 6 * 1600; /* 2 + 2 + 6 = 10 ticks: fmax = 62500 */
    T.maxvel[0] = 100;
    pluto_step_write(&T, 1000000);
    CHECK_EQ_INT(P.wreg[0], (int)(100 * 100 * 2048 * 1.6e-6 / 4));
    /* communication error: limits still computed, nothing written */
    T.communication_error = 3;
    clear_traces();
    T.steplen = 90000;
    log_clear();
    pluto_step_write(&T, 1000000);
    CHECK_EQ_STR(PC.log, "");
    CHECK_EQ_INT(T.steplen, 49600);
    epp_port_close(&PORT);
}

static void test_step_read(void)
{
    open_raw_pluto(0);
    step_setup(&PORT);
    T.scale[0] = 200;
    P.rreg[0] = 5 * 2048 + 1024; /* 5.5 steps */
    P.rreg[1] = 0x1FFFFF & (uint32_t)(-3 * 2048);
    P.rreg[4] = 0xBEEF;
    clear_traces();
    pluto_step_read(&T, 1000000);
    CHECK_EQ_INT(P.trace_len, strlen("A(00) ") + 20 * strlen("R(00) "));
    CHECK_EQ_INT(s_counts[0], 5);
    CHECK_NEAR(s_pfb[0], 5.5 / 200, 1e-12);
    CHECK_NEAR(s_vfb[0], 5.5 / 200 / 0.001, 1e-9);
    CHECK_EQ_INT(s_counts[1], -3);
    CHECK_EQ_INT(T.debug_0, 5 * 2048 + 1024);
    for (int i = 0; i < 16; i++)
        CHECK_EQ_INT(s_din[i], (0xBEEF >> i) & 1);
    /* 21-bit wrap: 600 periods of +400 steps */
    int64_t truth = 5 * 2048 + 1024;
    for (int k = 0; k < 600; k++) {
        truth += 400 * 2048;
        P.rreg[0] = (uint32_t)(truth & 0x1FFFFF);
        pluto_step_read(&T, 1000000);
    }
    CHECK_EQ_INT(s_counts[0], truth / 2048);
    CHECK_NEAR(s_vfb[0], 400.0 / 200 / 0.001, 1e-9);
    s_reset[0] = 1;
    pluto_step_read(&T, 1000000);
    CHECK_EQ_INT(s_counts[0], 0);
    CHECK(s_pfb[0] == 0.0);
    /* timeout */
    P.stall = 1;
    pluto_step_read(&T, 1000000);
    CHECK_EQ_INT(T.communication_error, 1);
    epp_port_close(&PORT);
}

/* ---- upload ------------------------------------------------------------- */

static void test_upload_raw(void)
{
    static uint8_t img[20000];
    for (size_t i = 0; i < sizeof(img); i++)
        img[i] = (uint8_t)xr();
    struct pluto_log log = {cap_log, NULL};
    open_raw_pluto(1);
    clear_traces();
    log_clear();
    CHECK_EQ_INT(pluto_upload(&PORT, img, 3, &log), 0);
    /* the exact line sequence for a 3-byte image */
    char want[8192];
    size_t n = 0;
    n += (size_t)snprintf(want + n, sizeof(want) - n, "outb(04,+2) outb(00,+1026) ");
    for (int i = 0; i < 4; i++)
        n += (size_t)snprintf(want + n, sizeof(want) - n, "outb(00,+2) ");
    for (int i = 0; i < 20; i++)
        n += (size_t)snprintf(want + n, sizeof(want) - n, "outb(04,+2) ");
    for (int k = 0; k < 3; k++)
        for (int b = 0; b < 8; b++)
            n += (size_t)snprintf(want + n, sizeof(want) - n,
                                  "outb(%s,+0) outb(04,+2) outb(05,+2) outb(04,+2) ",
                                  (img[k] >> b) & 1 ? "ff" : "00");
    n += (size_t)snprintf(want + n, sizeof(want) - n, "outb(80,+1026) ");
    CHECK_EQ_STR(PC.log, want);
    CHECK_EQ_STR(logbuf, "3:uploading firmware\n3:done\n");
    CHECK_EQ_INT(P.ninit_pulses, 1);
    CHECK_EQ_INT(P.ninit_low_writes, 4);
    CHECK_EQ_INT(P.ps_bits, 24);
    CHECK(memcmp(P.ps_bytes, img, 3) == 0);
    /* a full-size image: the first 19895 bytes are sent */
    PC.log_on = 0;
    CHECK_EQ_INT(pluto_upload(&PORT, img, sizeof(img), &log), 0);
    CHECK_EQ_INT(P.ps_bits, 8 * PLUTO_UPLOAD_BYTES);
    CHECK(memcmp(P.ps_bytes, img, PLUTO_UPLOAD_BYTES) == 0);
    CHECK_EQ_INT(P.ninit_pulses, 2);
    CHECK_EQ_INT(pluto_upload(&PORT, img, 0, &log), -EINVAL);
    CHECK_EQ_INT(pluto_upload(&PORT, NULL, 4, &log), -EINVAL);
    /* probe: the board answers */
    log_clear();
    CHECK_EQ_INT(pluto_probe(&PORT, "pluto-servo", &log), 0);
    CHECK_EQ_STR(logbuf, "");
    /* a board that stays unconfigured never acknowledges */
    P.stall = 1;
    CHECK_EQ_INT(pluto_probe(&PORT, "pluto-step", &log), -EIO);
    CHECK_EQ_STR(logbuf,
                 "1:Failed to communicate with pluto-step board after programming firmware.\n");
    CHECK_EQ_INT(PC.timeout, 0); /* cleared again */
    epp_port_close(&PORT);
}

static void test_upload_batched_and_gpiod(void)
{
    static uint8_t img[1500];
    for (size_t i = 0; i < sizeof(img); i++)
        img[i] = (uint8_t)xr();
    struct pluto_log log = {cap_log, NULL};
    periph_init(&P, PERIPH_PLUTO);
    pcport_init(&PC, &P);
    fake_batch_open(&PORT, &PC, 1);
    fake_batch_executes = 0;
    CHECK_EQ_INT(pluto_upload(&PORT, img, sizeof(img), &log), 0);
    CHECK_EQ_INT(fake_batch_executes, 3); /* 512-byte chunks */
    CHECK_EQ_INT(P.ps_bits, 8 * sizeof(img));
    CHECK(memcmp(P.ps_bytes, img, sizeof(img)) == 0);
    CHECK_EQ_INT(PC.ecr, 0x80);
    epp_port_close(&PORT);

    /* bit-banged: nInit on the 13th line */
    struct fake_lines f;
    char err[128];
    periph_init(&P, PERIPH_PLUTO);
    memset(&f, 0, sizeof(f));
    f.p = &P;
    struct epp_gpio_lines l = fake_gpio_lines(&f, 1);
    CHECK_EQ_INT(epp_gpiod_open(&PORT, &l, 10000, "gpiod:t", err, sizeof(err)), 0);
    CHECK_EQ_INT(pluto_upload(&PORT, img, 64, &log), 0);
    CHECK_EQ_INT(P.ninit_pulses, 1);
    CHECK_EQ_INT(P.ps_bits, 8 * 64);
    CHECK(memcmp(P.ps_bytes, img, 64) == 0);
    CHECK_EQ_INT(pluto_probe(&PORT, "pluto-servo", &log), 0);
    epp_port_close(&PORT);
}

static void test_read_firmware(void)
{
    uint8_t *buf = NULL;
    size_t len = 0;
    char path[512], err[512];
    CHECK_EQ_INT(pluto_read_firmware("", &buf, &len, path, sizeof(path), err, sizeof(err)),
                 -EINVAL);
    CHECK(pluto_read_firmware("/nonexistent/x.rbf", &buf, &len, path, sizeof(path), err,
                              sizeof(err)) < 0);
    CHECK(strstr(err, "/nonexistent/x.rbf") != NULL);
    setenv("HM2_FIRMWARE_PATH", "/nonexistent-dir", 1);
    CHECK_EQ_INT(pluto_read_firmware("pluto_servo.rbf", &buf, &len, path, sizeof(path), err,
                                     sizeof(err)),
                 -ENOENT);
    CHECK(strstr(err, "firmware 'pluto_servo.rbf' not found") != NULL);
    CHECK_EQ_INT(pluto_read_firmware("../etc/passwd", &buf, &len, path, sizeof(path), err,
                                     sizeof(err)),
                 -EINVAL);
    char tmpl[] = "/tmp/pluto-fw-XXXXXX";
    int fd = mkstemp(tmpl);
    CHECK(fd >= 0);
    close(fd);
    CHECK_EQ_INT(pluto_read_firmware(tmpl, &buf, &len, path, sizeof(path), err, sizeof(err)),
                 -EINVAL);
    CHECK(strstr(err, "has 0 bytes") != NULL);
    FILE *fp = fopen(tmpl, "wb");
    fwrite("abc", 1, 3, fp);
    fclose(fp);
    CHECK_EQ_INT(pluto_read_firmware(tmpl, &buf, &len, path, sizeof(path), err, sizeof(err)), 0);
    CHECK_EQ_INT(len, 3);
    free(buf);
    unlink(tmpl);
}

/* ---- parameter sanitizing, one test per parameter (LinuxCNC 2.9: spec
 * §4.2, §6.2).  Not sanitized there, nor here: encoder/stepgen scale (0
 * gives an infinite position, as in 2.9), pwm offset, stepspace (only
 * enters fmax). ---- */

static void test_sanitize_servo_max_dc(void)
{
    servo_setup(NULL);
    pwm_en[0] = 1;
    pwm_val[0] = 0.9;
    S.pwm_max_dc[0] = 1.5; /* above 1: 1 */
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 0), (int)(0.9 * 2047));
    CHECK(S.pwm_max_dc[0] == 1.0);
    S.pwm_max_dc[0] = -0.5; /* below 0: 0, output off */
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 0), 0);
    CHECK(S.pwm_max_dc[0] == 0.0);
    S.pwm_max_dc[0] = NAN; /* not a number: 1 */
    pluto_servo_pwm_word(&S, 0);
    CHECK(S.pwm_max_dc[0] == 1.0);
}

static void test_sanitize_servo_min_dc(void)
{
    servo_setup(NULL);
    pwm_en[0] = 1;
    pwm_val[0] = 0.01;
    S.pwm_max_dc[0] = 0.4;
    S.pwm_min_dc[0] = 0.7; /* above max-dc: max-dc */
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 0), (int)(0.4 * 2047));
    CHECK(S.pwm_min_dc[0] == 0.4);
    S.pwm_min_dc[0] = -0.3; /* below 0: 0 */
    CHECK_EQ_INT(pluto_servo_pwm_word(&S, 0), (int)(0.01 * 2047));
    CHECK(S.pwm_min_dc[0] == 0.0);
}

static void test_sanitize_step_maxvel(void)
{
    open_raw_pluto(1);
    P.pluto_step = 1;
    step_setup(&PORT);
    T.watchdog = 0;
    T.scale[1] = 10;
    T.maxvel[1] = -4; /* taken as 4 */
    s_en[1] = 1;
    s_cmd[1] = 100;
    log_clear();
    pluto_step_write(&T, 1000000);
    CHECK(T.maxvel[1] == 4.0);
    CHECK_EQ_STR(logbuf, "");
    CHECK_EQ_INT(P.wreg[1], (int)(4 * 10 * 2048 * 1.6e-6));
    epp_port_close(&PORT);
}

static void time_case(hal_u32_t *param, const char *what, int shift)
{
    open_raw_pluto(1);
    P.pluto_step = 1;
    step_setup(&PORT);
    T.watchdog = 0;
    *param = 1000000;
    log_clear();
    pluto_step_write(&T, 1000000);
    char want[160];
    snprintf(want, sizeof(want),
             "1:Requested %s 1000000ns decreased to 49600ns due to hardware limitations\n", what);
    CHECK_EQ_STR(logbuf, want);
    CHECK_EQ_INT(*param, 49600);
    CHECK_EQ_INT((P.wreg[5] >> shift) & 0x1F, 31);
    *param = 8000; /* in range: 5 ticks, kept */
    log_clear();
    pluto_step_write(&T, 1000000);
    CHECK_EQ_STR(logbuf, "");
    CHECK_EQ_INT(*param, 8000);
    CHECK_EQ_INT((P.wreg[5] >> shift) & 0x1F, 5);
    epp_port_close(&PORT);
}

static void test_sanitize_step_steplen(void)
{
    step_setup(NULL);
    time_case(&T.steplen, "step length", 0);
}

static void test_sanitize_step_dirtime(void)
{
    step_setup(NULL);
    time_case(&T.dirtime, "direction change time", 8);
}

int main(void)
{
    RUN(test_extend);
    RUN(test_servo_defaults);
    RUN(test_servo_pwm_word);
    RUN(test_servo_control_word);
    RUN(test_servo_write_cycles);
    RUN(test_servo_read);
    RUN(test_servo_comm_error);
    RUN(test_servo_batched_counts);
    RUN(test_step_defaults_and_words);
    RUN(test_step_write);
    RUN(test_step_limits_and_messages);
    RUN(test_step_read);
    RUN(test_upload_raw);
    RUN(test_upload_batched_and_gpiod);
    RUN(test_read_firmware);
    RUN(test_sanitize_servo_max_dc);
    RUN(test_sanitize_servo_min_dc);
    RUN(test_sanitize_step_maxvel);
    RUN(test_sanitize_step_steplen);
    RUN(test_sanitize_step_dirtime);
    return check_summary();
}
