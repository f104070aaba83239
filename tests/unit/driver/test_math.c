/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Driver maths (spec §10) against hand-computed values (the arithmetic is
 * written out next to each expectation) and trajectory properties.
 */
#include <math.h>
#include <stdint.h>

#include "../check.h"
#include "hm2/hm2.h"

static void test_stepgen_timing(void)
{
    bool clip;
    /* 5000 ns at 33.333333 MHz: 5000 * 0.033333333 = 166.67 -> 166 */
    CHECK_EQ_INT(hm2_stepgen_ns_to_clocks(5000, 33333333, &clip), 166);
    CHECK(!clip);
    /* 1000 ns at 50 MHz = 50 clocks exactly (no -1 applied) */
    CHECK_EQ_INT(hm2_stepgen_ns_to_clocks(1000, 50000000, &clip), 50);
    /* 327660 ns at 50 MHz = 16383 = 0x3FFF, the max */
    CHECK_EQ_INT(hm2_stepgen_ns_to_clocks(327660, 50000000, &clip), 0x3FFF);
    CHECK(!clip);
    CHECK_EQ_INT(hm2_stepgen_ns_to_clocks(327680, 50000000, &clip), 0x3FFF);
    CHECK(clip);
    CHECK_EQ_INT(hm2_stepgen_ns_to_clocks(0, 50000000, &clip), 0);
    CHECK_EQ_INT(hm2_stepgen_ns_to_clocks(0xFFFFFFFFu, 100000000, &clip), 0x3FFF);
    CHECK(clip);
    CHECK_NEAR(hm2_stepgen_clocks_to_ns(0x3FFF, 50000000), 327660.0, 1e-6);
    CHECK_NEAR(hm2_stepgen_clocks_to_ns(0x3FFF, 33333333), 491490.0049, 1e-3);
}

static void test_stepgen_maxvel_rate(void)
{
    /* steplen 5 us + stepspace 5 us -> 100 kHz; scale 400 steps/unit -> 250 */
    CHECK_NEAR(hm2_stepgen_physical_maxvel(5000, 5000, 400.0), 250.0, 1e-9);
    CHECK_NEAR(hm2_stepgen_physical_maxvel(5000, 5000, -400.0), 250.0, 1e-9);
    CHECK_NEAR(hm2_stepgen_physical_maxvel(0, 0, 400.0), 0.0, 0);
    /* rate = v * scale * 2^32 / ClockLow: 1 unit/s * 1000 steps/unit at
     * 50 MHz = 1000 * 4294967296 / 5e7 = 85899.34592 -> 85899 */
    CHECK_EQ_INT(hm2_stepgen_rate_register(1.0, 1000.0, 50000000), 85899);
    CHECK_EQ_INT((int32_t)hm2_stepgen_rate_register(-1.0, 1000.0, 50000000), -85899);
    /* 10 MHz step rate at 33.333333 MHz: 0.3 * 2^32 = 1288490198.4 */
    CHECK_EQ_INT(hm2_stepgen_rate_register(10e6, 1.0, 33333333), 1288490201);
    /* out of range is clamped, NaN gives 0 */
    CHECK_EQ_INT(hm2_stepgen_rate_register(1e12, 1.0, 33333333), 0x7FFFFFFF);
    CHECK_EQ_INT(hm2_stepgen_rate_register(-1e12, 1.0, 33333333), 0x80000000u);
    CHECK_EQ_INT(hm2_stepgen_rate_register(NAN, 1.0, 33333333), 0);
}

static void test_stepgen_accumulate(void)
{
    CHECK_EQ_INT(hm2_stepgen_accumulate(0, 0, 0x00030000), 0x30000);
    /* wrap forward: 0xFFFF0000 -> 0x00010000 is +2 steps */
    CHECK_EQ_INT(hm2_stepgen_accumulate(100, 0xFFFF0000u, 0x00010000u), 100 + 0x20000);
    /* wrap backward */
    CHECK_EQ_INT(hm2_stepgen_accumulate(0, 0x00010000u, 0xFFFF0000u), -0x20000);
    /* many wraps accumulate exactly (65536 steps per wrap, 2^32 units) */
    int64_t sub = 0;
    uint32_t acc = 0;
    for (int i = 0; i < 10 * 4096; i++) {
        uint32_t next = acc + 0x01000000u; /* +256 steps per read */
        sub = hm2_stepgen_accumulate(sub, acc, next);
        acc = next;
    }
    CHECK_EQ_INT(sub >> 16, 10 * 4096 * 256);
}

static void test_stepgen_position_control(void)
{
    /* Hand computation, T = 1 ms, cmd 0 -> 0.001, fb 0, vfb 0:
     * ff = 1; verr = -1.
     * maxaccel 1000: match_accel = +1000, t_match = 0.001 (not < T):
     *   pos_at_match = 0 + (1+0)/2 * 0.002 = 0.001, cmd_at_match = 0.002,
     *   err = -0.001; dv = -2, dp = -0.002, |err+2dp| = 0.005 > 0.001 keep;
     *   vcmd = 0 + 1000*0.001 = 1.0 */
    struct hm2_stepgen_posctl p = {.position_cmd = 0.001, .maxaccel = 1000.0, .period_s = 0.001};
    double v = hm2_stepgen_position_control(&p);
    CHECK_NEAR(v, 1.0, 1e-12);
    CHECK_NEAR(p.dbg_ff_vel, 1.0, 1e-12);
    CHECK_NEAR(p.dbg_vel_error, -1.0, 1e-12);
    CHECK_NEAR(p.dbg_s_to_match, 0.001, 1e-15);
    CHECK_NEAR(p.dbg_err_at_match, -0.001, 1e-15);
    CHECK_NEAR(p.old_position_cmd, 0.001, 0);
    /* maxaccel 1e6: t_match = 1e-6 < T:
     *   pos_at_match = 0.5 * (1e-6 + 1e-3) = 0.0005005;
     *   cmd_at_match = 0.001 + 1e-6 = 0.001001; err = -0.0005005;
     *   vcmd = 1 - 0.5 * (-0.0005005) / 0.001 = 1.25025 (within +-1000) */
    struct hm2_stepgen_posctl q = {.position_cmd = 0.001, .maxaccel = 1e6, .period_s = 0.001};
    CHECK_NEAR(hm2_stepgen_position_control(&q), 1.25025, 1e-12);
    /* maxaccel 0 (no limit), verr < 0: match_accel = verr/T = -1000,
     * t_match = -(-1)/(-1000) = -0.001 < T:
     *   pos_at_match = 0.5 * 0 = 0; cmd_at_match = 0.001 - 0.001 = 0;
     *   err = 0 -> vcmd = ff = 1 */
    struct hm2_stepgen_posctl r = {.position_cmd = 0.001, .maxaccel = 0, .period_s = 0.001};
    CHECK_NEAR(hm2_stepgen_position_control(&r), 1.0, 1e-12);
    /* standing still at the command: zero */
    struct hm2_stepgen_posctl s = {
        .position_cmd = 2, .position_fb = 2, .old_position_cmd = 2, .maxaccel = 10,
        .period_s = 0.001};
    CHECK_NEAR(hm2_stepgen_position_control(&s), 0.0, 1e-12);
}

/* Closed loop with an ideal stepper: a step command is reached, the
 * acceleration limit holds every period, and it settles. */
static void test_stepgen_trajectory(void)
{
    const double T = 0.001, maxaccel = 50.0, maxvel = 10.0;
    double fb = 0, vfb = 0, old = 0, peak_v = 0;
    int settled_at = -1;
    for (int i = 0; i < 5000; i++) {
        struct hm2_stepgen_posctl p = {.position_cmd = 1.0, .position_fb = fb, .velocity_fb = vfb,
                                       .maxaccel = maxaccel, .period_s = T,
                                       .old_position_cmd = old};
        double v = hm2_stepgen_position_control(&p);
        if (v > maxvel)
            v = maxvel;
        if (v < -maxvel)
            v = -maxvel;
        CHECK(fabs(v - vfb) <= maxaccel * T * (1 + 1e-9) + 1e-12);
        old = p.old_position_cmd;
        vfb = v;
        fb += v * T;
        if (fabs(v) > peak_v)
            peak_v = fabs(v);
        if (settled_at < 0 && fabs(fb - 1.0) < 1e-4 && fabs(v) < 1e-2)
            settled_at = i;
    }
    CHECK(settled_at > 0);
    CHECK(settled_at < 1000); /* 1 unit at 50 u/s^2: about 2*sqrt(1/50)=0.28 s */
    CHECK_NEAR(fb, 1.0, 1e-4);
    CHECK(peak_v <= maxvel);
    /* velocity mode acceleration limit */
    CHECK_NEAR(hm2_stepgen_velocity_control(10, 0, 100, 0.001), 0.1, 1e-12);
    CHECK_NEAR(hm2_stepgen_velocity_control(-10, 0, 100, 0.001), -0.1, 1e-12);
    CHECK_NEAR(hm2_stepgen_velocity_control(10, 0, 0, 0.001), 10, 0);
    CHECK_NEAR(hm2_stepgen_velocity_control(0.05, 0, 100, 0.001), 0.05, 0);
}

static void test_encoder_rates(void)
{
    /* TSDiv = floor(ClockLow/2e6) - 2: 33333333/2e6 = 16.67 -> 14 */
    CHECK_EQ_INT(hm2_encoder_tsdiv(33333333, false), 14);
    CHECK_EQ_INT(hm2_encoder_tsdiv(50000000, false), 23);
    CHECK_EQ_INT(hm2_encoder_tsdiv(50000000, true), 3);
    CHECK_EQ_INT(hm2_encoder_tsdiv(1000000, false), 0);
    CHECK_NEAR(hm2_encoder_seconds_per_tsc(50000000, 23), 25.0 / 50e6, 1e-18);
    uint32_t eff;
    /* 50 MHz / 25 MHz = 2 -> reg 0 (divide by 2) */
    CHECK_EQ_INT(hm2_encoder_qfilter_rate(50000000, 25000000, &eff), 0);
    CHECK_EQ_INT(eff, 25000000);
    /* 33.3 MHz / 25 MHz = 1 -> 0xFFF (divide by 1) */
    CHECK_EQ_INT(hm2_encoder_qfilter_rate(33333333, 25000000, &eff), 0xFFF);
    CHECK_EQ_INT(eff, 33333333);
    /* 50 MHz / 1 MHz = 50 -> 48, effective 1 MHz */
    CHECK_EQ_INT(hm2_encoder_qfilter_rate(50000000, 1000000, &eff), 48);
    CHECK_EQ_INT(eff, 1000000);
    /* 48 MHz / 7 MHz = 6 -> 4, effective 8 MHz */
    CHECK_EQ_INT(hm2_encoder_qfilter_rate(48000000, 7000000, &eff), 4);
    CHECK_EQ_INT(eff, 8000000);
    /* 0 Hz and tiny rates are bounded */
    CHECK_EQ_INT(hm2_encoder_qfilter_rate(50000000, 0, &eff), 0xFFF);
    CHECK_EQ_INT(hm2_encoder_qfilter_rate(50000000, 1, &eff), 0x7FF);
    CHECK_EQ_INT(eff, 50000000 / 0x801);
    CHECK_EQ_INT(hm2_wrap16(40000), 40000 - 65536);
    CHECK_EQ_INT(hm2_wrap16(-40000), -40000 + 65536);
    CHECK_EQ_INT(hm2_wrap16(32768), 32768);
    CHECK_EQ_INT(hm2_wrap16(-32768), -32768);
}

static struct hm2_encoder_sample S(uint16_t count, uint16_t ts, uint16_t tsc, uint32_t ccr)
{
    struct hm2_encoder_sample s = {(uint32_t)ts << 16 | count, ccr, tsc};
    return s;
}

static void test_encoder_velocity(void)
{
    /* tick 1 us, scale 100 counts/unit, vel-timeout 0.5 s */
    const double tick = 1e-6, scale = 100.0, to = 0.5;
    struct hm2_encoder_track t = {0};
    bool probe;
    struct hm2_encoder_sample s = S(0, 0, 1000, 0);
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    CHECK_EQ_INT(t.state, HM2_ENCODER_STOPPED);
    /* first counts: MOVING, no velocity yet */
    s = S(10, 2000, 2500, 0);
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    CHECK_EQ_INT(t.state, HM2_ENCODER_MOVING);
    CHECK_EQ_INT(t.rawcounts, 10);
    CHECK_NEAR(t.velocity, 0.0, 0);
    /* 50 counts in 1000 ticks: 0.5 unit / 1 ms = 500 units/s */
    s = S(60, 3000, 3500, 0);
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    CHECK_NEAR(t.velocity, 500.0, 1e-9);
    /* no new count, 4000 ticks since the last event: bound = 0.01/0.004 =
     * 2.5 units/s < 500 -> velocity drops to 2.5 */
    s = S(60, 3000, 7000, 0);
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    CHECK_NEAR(t.velocity, 2.5, 1e-9);
    /* timestamp rollovers: the TSCount wraps twice (2*65536 ticks) then
     * a count at ts 3000+... */
    s = S(60, 3000, 60000, 0);
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    s = S(60, 3000, 1000, 0); /* wrapped: +1 rollover */
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    s = S(61, 4000, 4000, 0); /* dT = (4000-3000) + 65536 ticks */
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    CHECK_NEAR(t.velocity, 0.01 / (66536 * 1e-6), 1e-9);
    /* direction change by one count: velocity 0 */
    s = S(60, 5000, 5000, 0);
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    CHECK_NEAR(t.velocity, 0.0, 0);
    CHECK_EQ_INT(t.rawcounts, 60);
    /* vel-timeout: 0.5 s = 500000 ticks = 7.6 rollovers without counts */
    for (int i = 0; i < 8 && t.state == HM2_ENCODER_MOVING; i++) {
        s = S(60, 5000, 60000, 0);
        hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
        s = S(60, 5000, 4000, 0);
        hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    }
    CHECK_EQ_INT(t.state, HM2_ENCODER_STOPPED);
    CHECK_NEAR(t.velocity, 0.0, 0);
    /* negative motion */
    s = S(50, 6000, 6000, 0);
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    s = S(40, 6100, 6100, 0); /* -10 counts in 100 us: -0.1/1e-4 = -1000 */
    hm2_encoder_track_update(&t, &s, scale, tick, to, &probe);
    CHECK_NEAR(t.velocity, -1000.0, 1e-9);
    CHECK_EQ_INT(t.rawcounts, 40);
}

static void test_encoder_latch(void)
{
    struct hm2_encoder_track t = {0};
    bool probe;
    struct hm2_encoder_sample s = S(65530, 0, 0, 0);
    t.prev_reg_count = 65530; /* primed as at load */
    hm2_encoder_track_update(&t, &s, 1, 1e-6, 0.5, &probe);
    CHECK_EQ_INT(t.rawcounts, 0);
    t.latch_pending = true;
    /* bit 4 still set: no event */
    s = S(65534, 10, 10, 1u << 4);
    CHECK_EQ_INT(hm2_encoder_track_update(&t, &s, 1, 1e-6, 0.5, &probe), 0);
    /* event latched at count 2 (wrapped from 65534: +4), now at 5 */
    s = S(5, 20, 20, 2u << 16);
    CHECK_EQ_INT(hm2_encoder_track_update(&t, &s, 1, 1e-6, 0.5, &probe), 1);
    CHECK_EQ_INT(t.zero_offset, 4 + 4);  /* prev_rawcounts 4 + wrap(2-65534)=4 */
    CHECK_EQ_INT(t.rawcounts, 11);
    CHECK(!t.latch_pending);
    /* probe latch */
    t.probe_pending = true;
    s = S(7, 30, 30, (6u << 16));
    hm2_encoder_track_update(&t, &s, 1, 1e-6, 0.5, &probe);
    CHECK(probe);
    CHECK_EQ_INT(t.rawlatch, 12);
}

static void test_pwmgen(void)
{
    /* 100 MHz: 12 bits up to 100e6/4096 = 24414 Hz */
    struct hm2_pwm_rate r = hm2_pwmgen_pwm_rate(20000, 100000000);
    CHECK_EQ_INT(r.bits, 12);
    CHECK_EQ_INT(r.dds, 53687); /* 20000*65536*4096/1e8 = 53687.09 */
    r = hm2_pwmgen_pwm_rate(24414, 100000000);
    CHECK_EQ_INT(r.bits, 12);
    r = hm2_pwmgen_pwm_rate(24415, 100000000);
    CHECK_EQ_INT(r.bits, 11);
    r = hm2_pwmgen_pwm_rate(100000, 100000000);
    CHECK_EQ_INT(r.bits, 9);
    CHECK_EQ_INT(r.dds, 33554); /* 1e5*65536*512/1e8 = 33554.43 */
    r = hm2_pwmgen_pwm_rate(200000, 100000000);
    CHECK(r.clipped);
    CHECK_EQ_INT(r.bits, 9);
    CHECK_EQ_INT(r.dds, 65535);
    CHECK_EQ_INT(r.frequency, 195309); /* 1e8*65535/(65536*512) = 195309.4 */
    r = hm2_pwmgen_pwm_rate(200000, 200000000);
    CHECK(!r.clipped);
    CHECK_EQ_INT(r.bits, 9);
    int clip;
    CHECK_EQ_INT(hm2_pwmgen_pdm_rate(20000, 100000000, &clip), 13);
    CHECK_EQ_INT(clip, 0);
    CHECK_EQ_INT(hm2_pwmgen_pdm_rate(1000, 100000000, &clip), 1);
    CHECK_EQ_INT(clip, -1);
    CHECK_EQ_INT(hm2_pwmgen_pdm_rate(200000000, 100000000, &clip), 65535);
    CHECK_EQ_INT(clip, 1);
    bool bad;
    CHECK_EQ_INT(hm2_pwmgen_mode_word(1, 12, false, &bad), 0x23);
    CHECK_EQ_INT(hm2_pwmgen_mode_word(2, 11, false, &bad), 0x2 | 0x10 | 0x20);
    CHECK_EQ_INT(hm2_pwmgen_mode_word(3, 9, false, &bad), 0x18);
    CHECK_EQ_INT(hm2_pwmgen_mode_word(4, 10, true, &bad), 0x1 | 0x08 | 0x20 | 0x40);
    CHECK(!bad);
    CHECK_EQ_INT(hm2_pwmgen_mode_word(0, 12, false, &bad), 0x23);
    CHECK(bad);
    /* values: 12-bit, 25 %: 0.25*4095 = 1023.75 -> *65536 = 67092480 */
    CHECK_EQ_INT(hm2_pwmgen_value_register(0.25, 1, true, 1, 12, false, false), 67092480);
    CHECK_EQ_INT(hm2_pwmgen_value_register(-0.25, 1, true, 1, 12, false, false),
                 0x80000000u | 67092480);
    CHECK_EQ_INT(hm2_pwmgen_value_register(5, 10, true, 1, 9, false, false),
                 (uint32_t)(0.5 * 511 * 65536));
    CHECK_EQ_INT(hm2_pwmgen_value_register(3, 1, true, 1, 9, false, false), 511u << 16);
    CHECK_EQ_INT(hm2_pwmgen_value_register(0.7, 1, false, 1, 12, false, false), 0);
    /* PDM uses 12 bits whatever the PWM resolution */
    CHECK_EQ_INT(hm2_pwmgen_value_register(1, 1, true, 3, 9, false, false), 4095u << 16);
    /* dither: t = 1.0625: 1*(4096-1.0625)*65536 */
    CHECK_EQ_INT(hm2_pwmgen_value_register(1, 1, true, 1, 12, false, true),
                 (uint32_t)(4094.9375 * 65536));
    /* offset mode, 12-bit PWM: bits 11: 0 -> 2048, +1 -> 2*2048-1, -1 -> 1 */
    CHECK_EQ_INT(hm2_pwmgen_value_register(0, 1, true, 1, 12, true, false), 2048u << 16);
    CHECK_EQ_INT(hm2_pwmgen_value_register(1, 1, true, 1, 12, true, false), 4095u << 16);
    CHECK_EQ_INT(hm2_pwmgen_value_register(-1, 1, true, 1, 12, true, false),
                 0x80000000u | (1u << 16));
    CHECK_EQ_INT(hm2_pwmgen_value_register(NAN, 1, true, 1, 12, false, false), 0);
    CHECK_EQ_INT(hm2_pwmgen_value_register(1, 0, true, 1, 12, false, false), 0);
}

static void test_watchdog(void)
{
    bool clip;
    /* 5 ms at 50 MHz: 250000 - 1 */
    CHECK_EQ_INT(hm2_watchdog_timer_value(5000000, 50000000, &clip), 249999);
    CHECK(!clip);
    /* 1 s at 33.333333 MHz: 33333333 - 1 */
    CHECK_EQ_INT(hm2_watchdog_timer_value(1000000000, 33333333, &clip), 33333332);
    /* unload: 1 ns -> below zero -> 0 (immediate bite) */
    CHECK_EQ_INT(hm2_watchdog_timer_value(1, 33333333, &clip), 0);
    /* 4.29 s at 1 GHz = 4.29e9 clocks > 2^31 */
    CHECK_EQ_INT(hm2_watchdog_timer_value(4000000000u, 1000000000, &clip), 0x7FFFFFFF);
    CHECK(clip);
    CHECK_EQ_INT(hm2_watchdog_max_timeout_ns(1000000000), 2147483647);
    CHECK_EQ_INT(hm2_watchdog_max_timeout_ns(33333333), 0xFFFFFFFFu);
}

int main(void)
{
    RUN(test_stepgen_timing);
    RUN(test_stepgen_maxvel_rate);
    RUN(test_stepgen_accumulate);
    RUN(test_stepgen_position_control);
    RUN(test_stepgen_trajectory);
    RUN(test_encoder_rates);
    RUN(test_encoder_velocity);
    RUN(test_encoder_latch);
    RUN(test_pwmgen);
    RUN(test_watchdog);
    return check_summary();
}
