/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * math_dump - runs the driver's maths (spec §10) over fixed scenarios and
 * prints the results, one "kind,inputs...,outputs..." line each, so
 * tests/driver/test_math_model.py can compare them with an independent
 * Python model of the spec.
 */
#include <inttypes.h>
#include <math.h>
#include <stdio.h>

#include "hm2/hm2.h"

static void stepgen_trajectories(void)
{
    static const struct {
        double maxaccel, maxvel, target, T;
        int ramp; /* 1: command ramps at 5 units/s, else a step */
    } sc[] = {{50, 10, 1.0, 0.001, 0}, {0, 10, 1.0, 0.001, 0}, {200, 3, -2.0, 0.001, 0},
              {20, 10, 0.5, 0.0005, 1}, {1000, 100, 0.3, 0.002, 1}, {0, 5, -0.7, 0.001, 1}};
    for (size_t k = 0; k < sizeof(sc) / sizeof(sc[0]); k++) {
        /* the motor moves exactly v*T; the feedback is quantized to whole
         * steps (1000 per unit) as the accumulator's integer part would be */
        double pos = 0, fb = 0, vfb = 0, old = 0;
        for (int i = 0; i < 1500; i++) {
            double cmd = sc[k].target;
            if (sc[k].ramp) {
                double r = 5.0 * i * sc[k].T * (sc[k].target < 0 ? -1 : 1);
                cmd = (sc[k].target < 0 ? (r < sc[k].target ? sc[k].target : r)
                                        : (r > sc[k].target ? sc[k].target : r));
            }
            struct hm2_stepgen_posctl p = {.position_cmd = cmd, .position_fb = fb,
                                           .velocity_fb = vfb, .maxaccel = sc[k].maxaccel,
                                           .period_s = sc[k].T, .old_position_cmd = old};
            double v = hm2_stepgen_position_control(&p);
            if (v > sc[k].maxvel)
                v = sc[k].maxvel;
            if (v < -sc[k].maxvel)
                v = -sc[k].maxvel;
            old = p.old_position_cmd;
            vfb = v;
            pos += v * sc[k].T;
            fb = floor(pos * 1000.0) / 1000.0;
            printf("traj,%zu,%d,%.17g,%.17g\n", k, i, v, pos);
        }
    }
}

static void stepgen_registers(void)
{
    static const uint32_t clocks[] = {33333333, 48000000, 50000000, 100000000};
    static const uint32_t ns[] = {0, 1, 20, 999, 5000, 100000, 327660, 491490, 491521, 4000000000u};
    static const double vel[] = {0, 1, -1, 12.5, -333.3, 1e5, 4e7};
    static const double scale[] = {1, 200, -200, 0.001};
    for (size_t c = 0; c < 4; c++) {
        for (size_t n = 0; n < sizeof(ns) / sizeof(ns[0]); n++) {
            bool clip;
            uint32_t r = hm2_stepgen_ns_to_clocks(ns[n], clocks[c], &clip);
            printf("sgtime,%u,%u,%u,%d\n", clocks[c], ns[n], r, clip);
        }
        for (size_t v = 0; v < sizeof(vel) / sizeof(vel[0]); v++)
            for (size_t s = 0; s < 4; s++)
                printf("sgrate,%u,%.17g,%.17g,%u\n", clocks[c], vel[v], scale[s],
                       hm2_stepgen_rate_register(vel[v], scale[s], clocks[c]));
    }
}

static void pwmgen_registers(void)
{
    static const uint32_t clocks[] = {96000000, 100000000, 200000000};
    static const uint32_t freqs[] = {1, 1000, 20000, 24414, 30000, 48828, 60000, 97656, 150000,
                                     195312, 400000, 2000000};
    static const double vals[] = {0, 0.1, -0.1, 0.5, -0.75, 1, -1, 1.5, 0.999};
    for (size_t c = 0; c < 3; c++) {
        for (size_t f = 0; f < sizeof(freqs) / sizeof(freqs[0]); f++) {
            struct hm2_pwm_rate r = hm2_pwmgen_pwm_rate(freqs[f], clocks[c]);
            int clip;
            uint32_t pdm = hm2_pwmgen_pdm_rate(freqs[f] * 100, clocks[c], &clip);
            printf("pwmrate,%u,%u,%d,%u,%d,%u\n", clocks[c], freqs[f], r.bits, r.dds, r.clipped,
                   pdm);
        }
    }
    for (int type = 1; type <= 4; type++)
        for (int bits = 9; bits <= 12; bits++)
            for (int off = 0; off <= 1; off++)
                for (int dither = 0; dither <= 1; dither++)
                    for (size_t v = 0; v < sizeof(vals) / sizeof(vals[0]); v++)
                        printf("pwmval,%d,%d,%d,%d,%.17g,%u\n", type, bits, off, dither, vals[v],
                               hm2_pwmgen_value_register(vals[v], 1.0, true, type, bits, off,
                                                         dither));
}

static void watchdog_and_encoder_registers(void)
{
    static const uint32_t clocks[] = {33333333, 48000000, 50000000, 100000000, 1000000000};
    static const uint32_t tmo[] = {1, 1000, 5000000, 1000000000, 4294967295u};
    static const uint32_t sf[] = {0, 1, 1000, 1000000, 7000000, 16000000, 25000000, 99000000};
    for (size_t c = 0; c < 5; c++) {
        for (size_t t = 0; t < 5; t++) {
            bool clip;
            printf("wd,%u,%u,%u\n", clocks[c], tmo[t],
                   hm2_watchdog_timer_value(tmo[t], clocks[c], &clip));
        }
        printf("tsdiv,%u,%u,%u\n", clocks[c], hm2_encoder_tsdiv(clocks[c], false),
               hm2_encoder_tsdiv(clocks[c], true));
        for (size_t f = 0; f < sizeof(sf) / sizeof(sf[0]); f++) {
            uint32_t eff;
            uint32_t r = hm2_encoder_qfilter_rate(clocks[c], sf[f], &eff);
            printf("qfilter,%u,%u,%u,%u\n", clocks[c], sf[f], r, eff);
        }
    }
}

/* A pseudo-random encoder: count moves by up to +-300 per read, the
 * timestamp of the last count advances, TSCount advances 1000 per read. */
static void encoder_sequence(void)
{
    struct hm2_encoder_track t = {0};
    uint32_t seed = 4242;
    uint16_t count = 50000, ts = 0, tsc = 0;
    t.prev_reg_count = count;
    for (int i = 0; i < 3000; i++) {
        seed = seed * 1103515245u + 12345u;
        int mode = (int)((seed >> 16) % 10);
        int delta = 0;
        if (mode < 5)
            delta = (int)((seed >> 8) % 601) - 300;
        else if (mode < 7)
            delta = (int)((seed >> 8) % 3) - 1;
        tsc = (uint16_t)(tsc + 1000);
        if (delta)
            ts = (uint16_t)(tsc - (uint16_t)((seed >> 4) % 1000));
        count = (uint16_t)(count + delta);
        struct hm2_encoder_sample s = {(uint32_t)ts << 16 | count, 0, tsc};
        bool probe;
        hm2_encoder_track_update(&t, &s, 4.0, 1e-6, 0.05, &probe);
        printf("enc,%d,%u,%u,%u,%" PRId32 ",%.17g,%d\n", i, count, ts, tsc, t.rawcounts,
               t.velocity, t.state);
    }
}

int main(void)
{
    stepgen_trajectories();
    stepgen_registers();
    pwmgen_registers();
    watchdog_and_encoder_registers();
    encoder_sequence();
    return 0;
}
