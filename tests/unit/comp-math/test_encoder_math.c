/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of host/hal/components/math/encoder_math.h against the rules
 * of docs/encoder.md, worked by hand; the component as a whole is compared
 * with LinuxCNC 2.9's recorded output by tests/hal/encoder-*.
 */
#include "check.h"
#include "math/encoder_math.h"

#define MS 1000000L

typedef struct {
    enc_t e;
    bool index_enable;
    double scale, min_speed;
    bool x4, counter;
    bool latch_rising, latch_falling;
} ch_t;

static void ch_init(ch_t *c)
{
    enc_init(&c->e);
    c->index_enable = false;
    c->scale = 1.0;
    c->min_speed = 1.0;
    c->x4 = true;
    c->counter = false;
    c->latch_rising = c->latch_falling = true;
}

/* One period: update-counters then capture-position. */
static void period(ch_t *c, int ab, bool z, bool latch, bool reset)
{
    enc_update(&c->e, ab & 1, ab >> 1, z, latch, c->latch_rising, c->latch_falling, c->x4,
               c->counter, MS);
    enc_capture(&c->e, &c->index_enable, &c->scale, &c->min_speed, reset);
}

/* A B as bits: forward order 00 10 11 01. */
static const int fwd[4] = {0, 1, 3, 2};

static void test_x4_counts_each_edge_and_ignores_glitches(void)
{
    ch_t c;
    ch_init(&c);
    for (int i = 1; i <= 8; i++)
        period(&c, fwd[i % 4], false, false, false);
    CHECK_EQ_INT(c.e.counts, 8);
    for (int i = 7; i >= 5; i--)
        period(&c, fwd[i % 4], false, false, false);
    CHECK_EQ_INT(c.e.counts, 5);
    period(&c, fwd[3], false, false, false); /* both phases change: ignored */
    CHECK_EQ_INT(c.e.counts, 5);
    CHECK_EQ_INT(c.e.raw, 5);
}

static void test_x1_and_counter_mode(void)
{
    ch_t c;
    ch_init(&c);
    c.x4 = false;
    for (int i = 1; i <= 8; i++)
        period(&c, fwd[i % 4], false, false, false);
    CHECK_EQ_INT(c.e.counts, 2); /* once per cycle: the 00 -> 10 step */
    period(&c, fwd[3], false, false, false);
    period(&c, fwd[2], false, false, false);
    period(&c, fwd[1], false, false, false);
    period(&c, fwd[0], false, false, false); /* 10 -> 00: back one */
    CHECK_EQ_INT(c.e.counts, 1);

    ch_t k;
    ch_init(&k);
    k.counter = true;
    int a[] = {1, 1, 0, 1, 0, 0, 1, 3, 2, 3};
    for (int i = 0; i < 10; i++)
        period(&k, a[i], false, false, false);
    CHECK_EQ_INT(k.e.counts, 4); /* rising edges of A, B ignored */
}

static void test_index_and_reset(void)
{
    ch_t c;
    ch_init(&c);
    for (int i = 1; i <= 5; i++)
        period(&c, fwd[i % 4], false, false, false);
    period(&c, fwd[6 % 4], true, false, false); /* Z without index-enable */
    CHECK_EQ_INT(c.e.counts, 6);
    c.index_enable = true;
    period(&c, fwd[7 % 4], false, false, false); /* arms */
    period(&c, fwd[8 % 4], true, false, false);  /* rising Z: counts 0 here */
    CHECK(!c.index_enable);
    CHECK_EQ_INT(c.e.counts, 0);
    CHECK_EQ_INT(c.e.raw, 8);
    period(&c, fwd[9 % 4], true, false, false);
    CHECK_EQ_INT(c.e.counts, 1);
    period(&c, fwd[10 % 4], false, false, true); /* reset */
    CHECK_EQ_INT(c.e.counts, 0);
    CHECK_NEAR(c.e.velocity, 0.0, 0.0);
}

static void test_latch_edges(void)
{
    ch_t c;
    ch_init(&c);
    c.latch_falling = false;
    period(&c, fwd[1], false, true, false); /* rising: latched at 1 */
    period(&c, fwd[2], false, true, false);
    period(&c, fwd[3], false, false, false); /* falling: not wanted */
    CHECK_EQ_INT(c.e.counts_latched, 1);
    c.latch_falling = true;
    period(&c, fwd[0], false, true, false);
    period(&c, fwd[1], false, false, false); /* falling: latched at 5 */
    CHECK_EQ_INT(c.e.counts_latched, 5);
    c.scale = 2.0;
    period(&c, fwd[1], false, false, true); /* reset: relative to the new zero */
    CHECK_EQ_INT(c.e.counts_latched, 0);
    CHECK_NEAR(c.e.position_latched, 0.0, 0.0);
}

static void test_velocity_estimate(void)
{
    ch_t c;
    ch_init(&c);
    c.scale = 4.0; /* counts per unit */
    /* a count every 2 ms: velocity after two counts, 0.5 counts/ms = 125 units/s */
    int s = 0;
    for (int i = 0; i < 12; i++) {
        if (i % 2 == 1)
            s++;
        period(&c, fwd[s % 4], false, false, false);
        if (i == 3)
            CHECK_NEAR(c.e.velocity, 0.0, 0.0);
    }
    CHECK_NEAR(c.e.velocity, 125.0, 1e-9);
    /* position-interpolated: one period after the last count */
    period(&c, fwd[s % 4], false, false, false);
    CHECK_NEAR(c.e.position_interp, c.e.position + 125.0 * 0.002, 1e-9);
    /* no counts: the estimate falls to the speed of a count arriving now
     * (12 ms after the last), and to 0 once the time since the last count
     * passes 1 / (min-speed-estimate / position-scale) s: 40 ms at 100 */
    c.min_speed = 100.0;
    for (int i = 0; i < 10; i++)
        period(&c, fwd[s % 4], false, false, false);
    CHECK_NEAR(c.e.velocity, 0.25 / 0.012, 1e-9);
    for (int i = 0; i < 27; i++)
        period(&c, fwd[s % 4], false, false, false);
    CHECK(c.e.velocity > 0.0); /* 39 ms */
    period(&c, fwd[s % 4], false, false, false);
    CHECK_NEAR(c.e.velocity, 0.0, 0.0); /* 40 ms */
}

static void test_zero_scale_and_min_speed(void)
{
    ch_t c;
    ch_init(&c);
    c.scale = 0.0;
    c.min_speed = 0.0;
    period(&c, 0, false, false, false);
    CHECK_NEAR(c.scale, 1.0, 0.0);     /* written back as 2.9 does */
    CHECK_NEAR(c.min_speed, 1.0, 0.0); /* 0 means the default */
}

int main(void)
{
    RUN(test_x4_counts_each_edge_and_ignores_glitches);
    RUN(test_x1_and_counter_mode);
    RUN(test_index_and_reset);
    RUN(test_latch_edges);
    RUN(test_velocity_estimate);
    RUN(test_zero_scale_and_min_speed);
    return check_summary();
}
