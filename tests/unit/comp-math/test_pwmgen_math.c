/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of host/hal/components/math/pwmgen_math.h against the rules
 * of docs/pwmgen.md, worked by hand; the component as a whole is compared
 * with LinuxCNC 2.9's recorded output by tests/hal/pwmgen-*.
 */
#include "check.h"
#include "math/pwmgen_math.h"

#define US 1000L

typedef struct {
    pwm_t p;
    pwm_pulse_t q;
    pwm_settings_t s;
    double offset;
    bool dither, bipolar;
} ch_t;

static void ch_init(ch_t *c, double freq)
{
    pwm_init(&c->p, &c->q);
    c->s = (pwm_settings_t){freq, 1.0, 0.0, 1.0};
    c->offset = 0.0;
    c->dither = false;
    c->bipolar = true;
}

/* n periods of make-pulses then update; returns how many had the output high. */
static int run(ch_t *c, int n, long period, double value, bool enable)
{
    int high = 0;
    for (int i = 0; i < n; i++) {
        pwm_make_pulses(&c->q, period);
        pwm_update(&c->p, &c->q, period, &c->s, value, c->offset, enable, c->dither, c->bipolar);
        high += c->q.out;
    }
    return high;
}

static void test_pure_pwm_rounds_to_whole_periods(void)
{
    ch_t c;
    ch_init(&c, 700.0);
    run(&c, 1, 100 * US, 0.1, true);
    /* 1/700 s = 14.29 periods of 100 us: 14, so 714.29 Hz */
    CHECK_EQ_INT(c.p.periods, 14);
    CHECK_NEAR(c.s.freq, 1e9 / 1400000.0, 1e-9);
    /* 0.1 x 14 = 1.4 periods high: 1, curr-dc 1/14 */
    CHECK_NEAR(c.p.curr_dc, 1.0 / 14.0, 1e-15);
    CHECK_EQ_INT(c.q.high_time, 100000);
    /* over 10 PWM periods: high exactly 10 make-pulses periods */
    CHECK_EQ_INT(run(&c, 140, 100 * US, 0.1, true), 10);
}

static void test_frequency_limits(void)
{
    ch_t c;
    ch_init(&c, 20000.0);
    run(&c, 1, 100 * US, 0.5, true);
    CHECK_NEAR(c.s.freq, 5000.0, 0.0); /* at most one PWM period per 2 make-pulses periods */
    ch_init(&c, 0.3);
    c.dither = true;
    run(&c, 1, 100 * US, 0.5, true);
    CHECK_NEAR(c.s.freq, 0.5, 0.0);
    ch_init(&c, -3.0);
    run(&c, 1, 100 * US, 0.5, true);
    CHECK_NEAR(c.s.freq, 0.0, 0.0);
    CHECK_EQ_INT(c.q.mode, PWM_PURE); /* chosen before pwm-freq was corrected; PDM from the next update on */
    run(&c, 1, 100 * US, 0.5, true);
    CHECK_EQ_INT(c.q.mode, PWM_PDM);
}

static void test_update_before_make_pulses(void)
{
    ch_t c;
    ch_init(&c, 1000.0);
    pwm_update(&c.p, &c.q, PWM_NO_PERIOD, &c.s, 0.5, 0.0, true, false, true);
    CHECK_NEAR(c.s.freq, -5e8, 0.0); /* as 2.9: the limit with a period of -1 ns */
    pwm_make_pulses(&c.q, 100 * US);
    pwm_update(&c.p, &c.q, 100 * US, &c.s, 0.5, 0.0, true, false, true);
    CHECK_NEAR(c.s.freq, 0.0, 0.0);
}

static void test_dither_carries_the_rounding(void)
{
    ch_t c;
    ch_init(&c, 1300.0);
    c.dither = true;
    /* 769230 ns period, 25%: 192308 ns high, about 1.92 periods of 100 us */
    int high = run(&c, 7692, 100 * US, 0.25, true);
    CHECK_EQ_INT(c.q.period, 769230);
    CHECK_EQ_INT(c.q.high_time, 192308);
    CHECK(high >= 1920 && high <= 1926);
}

static void test_pdm_density(void)
{
    ch_t c;
    ch_init(&c, 0.0);
    CHECK_EQ_INT(run(&c, 1000, 50 * US, 0.3, true), 300);
    CHECK_EQ_INT(run(&c, 1000, 50 * US, -0.3, true), 300);
    CHECK(c.q.direction);
    CHECK_EQ_INT(run(&c, 10, 50 * US, 0.3, false), 0);
}

static void test_limits_and_unipolar(void)
{
    ch_t c;
    ch_init(&c, 0.0);
    c.s.max_dc = 1.5;
    c.s.min_dc = -0.2;
    run(&c, 1, 50 * US, 0.5, true);
    CHECK_NEAR(c.s.max_dc, 1.0, 0.0);
    CHECK_NEAR(c.s.min_dc, 0.0, 0.0);
    c.s.max_dc = 0.4;
    c.s.min_dc = 0.7;
    run(&c, 1, 50 * US, 0.01, true);
    CHECK_NEAR(c.s.min_dc, 0.4, 0.0); /* min-dc above max-dc: lowered to it */
    CHECK_NEAR(c.p.curr_dc, 0.4, 0.0);
    run(&c, 1, 50 * US, -0.9, true);
    CHECK_NEAR(c.p.curr_dc, -0.4, 0.0);
    c.bipolar = false;
    run(&c, 1, 50 * US, -0.9, true);
    CHECK_NEAR(c.p.curr_dc, 0.4, 0.0); /* negative -> 0 -> min-dc */
    CHECK(!c.q.direction);
}

static void test_scale_quirks(void)
{
    ch_t c;
    ch_init(&c, 0.0);
    c.s.scale = 2.0; /* set before the first update: 2.9 keeps scale_recip 0 */
    c.offset = 0.1;
    run(&c, 1, 50 * US, 0.9, true);
    CHECK_NEAR(c.p.curr_dc, 0.1, 0.0);
    c.s.scale = 4.0;
    run(&c, 1, 50 * US, 0.8, true);
    CHECK_NEAR(c.p.curr_dc, 0.3, 1e-15);
    c.s.scale = 1e-21;
    run(&c, 1, 50 * US, 0.2, true);
    CHECK_NEAR(c.s.scale, 1.0, 0.0);
    CHECK_NEAR(c.p.curr_dc, 0.3, 1e-15);
}

static void test_nan_value(void)
{
    ch_t c;
    ch_init(&c, 1000.0);
    run(&c, 1, 100 * US, NAN, true);
    CHECK(c.q.direction);
    CHECK_NEAR(c.p.curr_dc, INT32_MIN / 10.0, 1e-6); /* -(INT_MIN) wraps in 2.9 */
    CHECK_EQ_INT(c.q.high_time, 0);                  /* INT_MIN x 100000 wraps to 0 */
    CHECK_EQ_INT(pwm_to_int(INFINITY), INT32_MIN);
    CHECK_EQ_INT(pwm_to_int(-2147483648.9), INT32_MIN);
    CHECK_EQ_INT(pwm_to_int(2147483647.9), INT32_MAX);
}

int main(void)
{
    RUN(test_pure_pwm_rounds_to_whole_periods);
    RUN(test_frequency_limits);
    RUN(test_update_before_make_pulses);
    RUN(test_dither_carries_the_rounding);
    RUN(test_pdm_density);
    RUN(test_limits_and_unipolar);
    RUN(test_scale_quirks);
    RUN(test_nan_value);
    return check_summary();
}
