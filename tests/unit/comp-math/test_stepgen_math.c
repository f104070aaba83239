/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of host/hal/components/math/stepgen_math.h against the rules
 * of docs/stepgen.md, worked by hand; the component as a whole is compared
 * with LinuxCNC 2.9's recorded output by tests/hal/stepgen-*.
 */
#include <string.h>

#include "check.h"
#include "math/stepgen_math.h"

#define MS 1000000L

typedef struct {
    sg_chan_t c;
    sg_timebase_t tb;
} gen_t;

static int reports;
static int reported_want, reported_limit;

static void too_fast(int chan, int want, int limit)
{
    (void)chan;
    reports++;
    reported_want = want;
    reported_limit = limit;
}

static void gen_init(gen_t *g, int type, bool pos, const int *user, int user_len)
{
    sg_timebase_init(&g->tb);
    sg_chan_init(&g->c, type, pos, user, user_len);
}

/* One servo period with make-pulses in the same thread: make-pulses,
 * then update-freq (the order the tests/hal recordings use). */
static void period(gen_t *g, double cmd, bool enable)
{
    g->tb.make_period = MS;
    sg_make_pulses(&g->c, enable, MS);
    sg_timebase_update(&g->tb, MS);
    sg_update_freq(&g->c, &g->tb, enable, cmd, 0, too_fast);
}

static double fb(gen_t *g)
{
    int32_t counts;
    double pos;
    sg_capture(&g->c, &counts, &pos);
    return pos;
}

static void test_patterns_and_user_table(void)
{
    CHECK_EQ_INT(sg_patterns[2].len, 4);
    CHECK_EQ_INT(sg_patterns[14].phases, 5);
    for (int t = 2; t <= 14; t++) {
        /* each state differs from the next in the pattern */
        const sg_pattern_t *p = &sg_patterns[t];
        for (int i = 0; i < p->len; i++)
            CHECK(p->state[i] != p->state[(i + 1) % p->len]);
        CHECK(p->state[0] < (1 << p->phases));
    }
    int user[] = {1, 3, 2, 6, 4, 5};
    CHECK_EQ_INT(sg_user_phases(user, 6), 3);
    int big[] = {1, 32};
    CHECK_EQ_INT(sg_user_phases(big, 2), -1);
    int neg[] = {-5};
    CHECK_EQ_INT(sg_user_phases(neg, 1), -1);
    CHECK_EQ_INT(sg_user_phases(user, 0), 0);
}

static void test_velocity_dds_and_phases(void)
{
    gen_t g;
    gen_init(&g, 3, false, NULL, 0);
    CHECK_EQ_INT(g.c.out, 1); /* state 0: phase A */
    period(&g, 250.0, true);  /* 250 steps/s = 1/4 step per period */
    CHECK_EQ_INT(g.c.target_addval, SG_ONE_STEP / 4);
    period(&g, 250.0, true);
    CHECK_NEAR(fb(&g), 0.25, 1e-12);
    period(&g, 250.0, true); /* reaches 0.5: the first step */
    CHECK_EQ_INT(g.c.rawcount, 1);
    CHECK_EQ_INT(g.c.out, 2); /* phase B */
    for (int i = 0; i < 4; i++)
        period(&g, 250.0, true);
    CHECK_EQ_INT(g.c.rawcount, 2);
    CHECK_EQ_INT(g.c.out, 4);
    CHECK_NEAR(g.c.freq, 250.0, 0.0);
    period(&g, 0.0, false); /* disabled: frequency 0 at once */
    CHECK_NEAR(g.c.freq, 0.0, 0.0);
}

static void test_user_pattern_backwards(void)
{
    gen_t g;
    int user[] = {1, 3, 2};
    gen_init(&g, SG_USER_TYPE, false, user, 3);
    period(&g, -500.0, true);
    period(&g, -500.0, true); /* position -0.5: not yet past the middle */
    CHECK_EQ_INT(g.c.rawcount, 0);
    period(&g, -500.0, true); /* -1.0: the first step down */
    CHECK_EQ_INT(g.c.rawcount, -1);
    CHECK_EQ_INT(g.c.out, 2); /* wrapped to the last state */
    period(&g, -500.0, true);
    period(&g, -500.0, true);
    CHECK_EQ_INT(g.c.out, 3);
}

static void test_timing_rounding_and_limits(void)
{
    gen_t g;
    gen_init(&g, 0, false, NULL, 0);
    g.c.steplen = 1500000;
    g.c.stepspace = 0;
    g.c.dirhold = 0;
    g.c.dirsetup = 0;
    g.c.maxvel = 1000;
    reports = 0;
    period(&g, 1000.0, true);
    CHECK_EQ_INT(g.c.steplen, 2000000);
    CHECK_EQ_INT(g.c.stepspace, 0);
    CHECK_EQ_INT(g.c.dirhold, 1000000); /* type 0: at least a period */
    CHECK_EQ_INT(g.c.dirsetup, 0);
    /* 1 / 2 ms = 500 steps/s: maxvel lowered, reported once */
    CHECK_NEAR(g.c.maxvel, 500.0, 1e-9);
    CHECK_EQ_INT(reports, 1);
    CHECK_EQ_INT(reported_want, 1000);
    CHECK_EQ_INT(reported_limit, 500);
    g.c.maxvel = 2000;
    period(&g, 1000.0, true);
    CHECK_EQ_INT(reports, 1);
    CHECK_NEAR(g.c.freq, 500.0, 1e-9);
    g.c.maxvel = -3;
    g.c.maxaccel = -7;
    period(&g, 1000.0, true);
    CHECK_NEAR(g.c.maxvel, 0.0, 0.0);
    CHECK_NEAR(g.c.maxaccel, 0.0, 0.0);

    gen_t q;
    gen_init(&q, 2, false, NULL, 0);
    q.c.dirdelay = 0;
    period(&q, 0.0, true);
    CHECK_EQ_INT(q.c.dirdelay, 0); /* may be 0 for types 2-15 */
    gen_t u;
    gen_init(&u, 1, false, NULL, 0);
    u.c.dirdelay = 0;
    period(&u, 0.0, true);
    CHECK_EQ_INT(u.c.dirdelay, 1000000); /* not for type 1 */
    CHECK_EQ_INT(sg_round_up(UINT32_MAX, MS), UINT32_MAX / MS * MS);
}

static void test_maxaccel_ramp(void)
{
    gen_t g;
    gen_init(&g, 2, false, NULL, 0);
    g.c.maxaccel = 50000; /* 50 steps/s per 1 ms period */
    period(&g, 500.0, true);
    CHECK_NEAR(g.c.freq, 50.0, 1e-9);
    period(&g, 500.0, true);
    CHECK_NEAR(g.c.freq, 100.0, 1e-9);
    for (int i = 0; i < 20; i++)
        period(&g, 500.0, true);
    CHECK_NEAR(g.c.freq, 500.0, 1e-9);
}

/* Type 0 with steplen 1, dirhold 2, dirsetup 1 periods: after a step at
 * period k the dir output may change at k+3 and the next step the other
 * way may come at k+4; the generator stands still in between. */
static void test_reversal_waits_for_dirhold_and_dirsetup(void)
{
    gen_t g;
    gen_init(&g, 0, false, NULL, 0);
    g.c.stepspace = 0;
    g.c.dirhold = 2000000;
    g.c.dirsetup = 1000000;
    period(&g, 500.0, true); /* sets the target */
    period(&g, 500.0, true); /* 0.5: a step, k = this period */
    CHECK_EQ_INT(g.c.rawcount, 1);
    CHECK(g.c.out & SG_OUT_STEP);
    CHECK(!(g.c.out & SG_OUT_DIR));
    period(&g, -500.0, true); /* k+1: still forward (target set now) */
    double p = fb(&g);
    CHECK_NEAR(p, 1.0, 1e-12);
    CHECK(!(g.c.out & SG_OUT_STEP)); /* pulse over after steplen */
    period(&g, -500.0, true); /* k+2: frozen */
    CHECK_NEAR(fb(&g), p, 0.0);
    CHECK(!(g.c.out & SG_OUT_DIR));
    period(&g, -500.0, true); /* k+3: dir changes, still frozen */
    CHECK_NEAR(fb(&g), p, 0.0);
    CHECK(g.c.out & SG_OUT_DIR);
    period(&g, -500.0, true); /* k+4: moving back */
    CHECK_NEAR(fb(&g), p - 0.5, 1e-12);
}

static void test_position_mode(void)
{
    gen_t g;
    gen_init(&g, 0, true, NULL, 0);
    g.c.scale = 100;
    g.c.maxvel = 2;
    g.c.maxaccel = 20;
    double prev = 0.0, vmax = 0.0;
    for (int i = 0; i < 2000; i++) {
        period(&g, 1.0, true);
        double now = fb(&g);
        double v = (now - prev) / 0.001;
        if (v > vmax)
            vmax = v;
        prev = now;
    }
    CHECK_EQ_INT(g.c.rawcount, 100);
    CHECK_NEAR(fb(&g), 1.0, 0.005);
    CHECK(vmax <= 2.0 * 1.0001 && vmax > 1.99);
    CHECK_NEAR(g.c.freq, 0.0, 1e-6);
}

static void test_scale_guard(void)
{
    gen_t g;
    gen_init(&g, 2, false, NULL, 0);
    g.c.scale = 1e-21;
    period(&g, 10.0, true);
    CHECK_NEAR(g.c.scale, 1.0, 0.0);
    CHECK_NEAR(g.c.freq, 10.0, 1e-12);
}

int main(void)
{
    RUN(test_patterns_and_user_table);
    RUN(test_velocity_dds_and_phases);
    RUN(test_user_pattern_backwards);
    RUN(test_timing_rounding_and_limits);
    RUN(test_maxaccel_ramp);
    RUN(test_reversal_waits_for_dirhold_and_dirsetup);
    RUN(test_position_mode);
    RUN(test_scale_guard);
    return check_summary();
}
