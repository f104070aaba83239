/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of host/hal/components/math/pid_math.h against hand-worked
 * values of the formulas in docs/pid.md (LinuxCNC 2.9's pid(9)); the
 * component as a whole is compared with LinuxCNC's recorded output by
 * tests/hal/pid-*.
 */
#include <math.h>
#include <string.h>

#include "check.h"
#include "math/pid_math.h"

#define MS 1000000L /* a 1 ms period */

typedef struct {
    pid_state_t s;
    pid_tune_t t;
    pid_inputs_t in;
    pid_gains_t g;
} loop_t;

static void loop_init(loop_t *l)
{
    memset(l, 0, sizeof *l);
    l->g.kp = 1.0;
    l->in.prev_target = true;
    l->in.on = true;
    l->t.cycles = 50;
    l->t.effort = 0.5;
}

static void step(loop_t *l, double cmd, double fb)
{
    l->in.cmd = cmd;
    l->in.fb = fb;
    pid_step(&l->s, &l->t, &l->in, &l->g, MS);
}

static void test_proportional_and_previous_target(void)
{
    loop_t l;
    loop_init(&l);
    l.g.kp = 2.0;
    step(&l, 1.0, 0.0); /* error from the previous command (0) */
    CHECK_NEAR(l.s.err, 0.0, 1e-12);
    CHECK_NEAR(l.s.out, 0.0, 1e-12);
    step(&l, 1.0, 0.25);
    CHECK_NEAR(l.s.err, 0.75, 1e-12);
    CHECK_NEAR(l.s.out, 1.5, 1e-12);
    l.in.prev_target = false;
    step(&l, 3.0, 0.25);
    CHECK_NEAR(l.s.err, 2.75, 1e-12);
    CHECK_NEAR(l.s.out, 5.5, 1e-12);
}

static void test_maxerror_then_deadband(void)
{
    loop_t l;
    loop_init(&l);
    l.in.prev_target = false;
    l.g.lim_err = 1.5;
    l.g.db = 0.6;
    step(&l, 2.0, 0.0); /* 2 -> 1.5 -> 0.9 */
    CHECK_NEAR(l.s.err, 2.0, 1e-12);
    CHECK_NEAR(l.s.out, 0.9, 1e-12);
    step(&l, -0.5, 0.0); /* inside the deadband */
    CHECK_NEAR(l.s.out, 0.0, 1e-12);
    step(&l, -1.0, 0.0); /* -1 -> -0.4 */
    CHECK_NEAR(l.s.out, -0.4, 1e-12);
}

static void test_integrator_holds_at_the_limit(void)
{
    loop_t l;
    loop_init(&l);
    l.in.prev_target = false;
    l.g.kp = 0.0;
    l.g.ki = 100.0;
    l.g.lim_out = 0.5;
    step(&l, 1.0, 0.0); /* errorI 0.001, output 0.1 */
    CHECK_NEAR(l.s.err_i, 0.001, 1e-15);
    CHECK_NEAR(l.s.out, 0.1, 1e-12);
    CHECK(!l.s.sat);
    l.g.ki = 1000.0;
    step(&l, 1.0, 0.0); /* 0.002 * 1000 = 2 -> clamped */
    CHECK_NEAR(l.s.out, 0.5, 1e-12);
    CHECK(l.s.sat);
    CHECK_EQ_INT(l.s.sat_count, 1);
    step(&l, 1.0, 0.0); /* same side: holds */
    CHECK_NEAR(l.s.err_i, 0.002, 1e-15);
    CHECK_EQ_INT(l.s.sat_count, 2);
    CHECK_NEAR(l.s.sat_s, 0.002, 1e-15);
    step(&l, -1.0, 0.0); /* the other side: integrates */
    CHECK_NEAR(l.s.err_i, 0.001, 1e-15);
    l.g.lim_out = 0.0; /* no limit: the clamp state stays as it was */
    step(&l, -1.0, 0.0);
    CHECK(l.s.sat);
    l.in.on = false;
    step(&l, -1.0, 0.0);
    CHECK(!l.s.sat);
    CHECK_NEAR(l.s.out, 0.0, 0.0);
    CHECK_NEAR(l.s.err_i, 0.0, 0.0);
    CHECK_EQ_INT(l.s.sat_count, 0);
}

static void test_maxerror_i(void)
{
    loop_t l;
    loop_init(&l);
    l.in.prev_target = false;
    l.g.lim_err_i = 0.0025;
    for (int i = 0; i < 5; i++)
        step(&l, 1.0, 0.0);
    CHECK_NEAR(l.s.err_i, 0.0025, 1e-15);
}

static void test_derivatives_and_feed_forward(void)
{
    loop_t l;
    loop_init(&l);
    l.g.kp = 0.0;
    l.g.ff0 = 1.0;
    l.g.ff1 = 0.1;
    l.g.ff2 = 0.01;
    step(&l, 0.001, 0.0); /* commandD 1, commandDD 1000 */
    CHECK_NEAR(l.s.cmd_d, 1.0, 1e-9);
    CHECK_NEAR(l.s.cmd_dd, 1000.0, 1e-6);
    CHECK_NEAR(l.s.cmd_ddd, 1e6, 1e-3);
    CHECK_NEAR(l.s.out, 0.001 + 0.1 + 10.0, 1e-9);
    l.g.lim_cmd_d = 0.5; /* the limited commandD feeds commandDD ... */
    step(&l, 0.003, 0.001);
    CHECK_NEAR(l.s.cmd_d, 0.5, 1e-12);
    CHECK_NEAR(l.s.cmd_dd, -500.0, 1e-6);
    /* ... errorD sees the unlimited one: 2 - 1 */
    CHECK_NEAR(l.s.err_d, 1.0, 1e-9);
    l.g.lim_err_d = 0.25;
    step(&l, 0.006, 0.001);
    CHECK_NEAR(l.s.err_d, 0.25, 1e-12);
}

static void test_index_enable_falling_edge(void)
{
    loop_t l;
    loop_init(&l);
    step(&l, 1.0, 0.0);
    l.in.index = true;
    step(&l, 2.0, 1.0);
    CHECK_NEAR(l.s.cmd_d, 1000.0, 1e-9);
    l.in.index = false; /* position reset: derivatives held, error from now */
    step(&l, -7.0, -8.0);
    CHECK_NEAR(l.s.cmd_d, 1000.0, 1e-9);
    CHECK_NEAR(l.s.err, 1.0, 1e-12);
    CHECK_NEAR(l.s.err_d, 0.0, 1e-9); /* held commandD - held feedback derivative */
    step(&l, -6.0, -8.0);
    CHECK_NEAR(l.s.cmd_d, 1000.0, 1e-9);
    CHECK_NEAR(l.s.err, 1.0, 1e-12); /* previous command -7 */
}

static void test_connected_derivative_pins(void)
{
    loop_t l;
    loop_init(&l);
    l.in.cmd_d_given = l.in.fb_d_given = true;
    l.in.cmd_d_in = 5.0;
    l.in.fb_d_in = 2.0;
    step(&l, 100.0, 0.0);
    CHECK_NEAR(l.s.cmd_d, 5.0, 0.0);
    CHECK_NEAR(l.s.err_d, 3.0, 0.0);
}

static void test_nan_error_does_not_integrate(void)
{
    loop_t l;
    loop_init(&l);
    l.in.prev_target = false;
    step(&l, 1.0, 0.0);
    step(&l, INFINITY, 0.0); /* 0 * inf is NaN: the integrator holds */
    CHECK_NEAR(l.s.err_i, 0.001, 1e-15);
    step(&l, 1.0, NAN);
    CHECK_NEAR(l.s.err_i, 0.001, 1e-15);
    CHECK(isnan(l.s.out));
}

static void test_tune_type0(void)
{
    loop_t l;
    loop_init(&l);
    l.in.prev_target = false;
    l.g.offset = 0.1;
    l.g.ff1 = 0.75;
    l.t.active = true;
    l.t.start = true;
    l.t.cycles = 4;
    l.t.effort = 1.0;
    step(&l, 0.0, -2.0); /* entering tune mode: output 0 */
    CHECK_NEAR(l.s.out, 0.0, 0.0);
    CHECK(l.t.mode == PID_MODE_IDLE);
    step(&l, 0.0, -2.0); /* idle sees tune-start */
    CHECK(l.t.mode == PID_MODE_START);
    step(&l, 0.0, -2.0); /* relay starts high */
    CHECK_NEAR(l.s.out, 1.1, 1e-12);
    /* with the start period, the error is +2 for 5 periods, -2 for 5, ...:
     * the relay switches every 5 periods */
    for (int i = 0; i < 19; i++)
        step(&l, 0.0, (((i + 1) / 5) % 2 == 0) ? -2.0 : 2.0);
    CHECK(l.t.start);
    CHECK_NEAR(l.s.out, -0.9, 1e-12);
    step(&l, 0.0, -2.0); /* 4th switch: done */
    CHECK(!l.t.start);
    CHECK(l.t.gains_found);
    CHECK_NEAR(l.s.out, 0.1, 1e-12);
    double ku = 4.0 / (PID_PI * 2.0);
    CHECK_NEAR(l.t.ku, ku, 1e-12);
    CHECK_NEAR(l.t.pu, 0.010, 1e-12); /* 20 periods / 2 cycles */
    CHECK_NEAR(l.g.kp, 0.6 * ku, 1e-12);
    CHECK_NEAR(l.g.ki, 2 * 0.6 * ku / 0.010, 1e-9);
    CHECK_NEAR(l.g.kd, 0.6 * ku * 0.010 / 8, 1e-12);
    CHECK_NEAR(l.g.ff1, 0.0, 0.0);
    step(&l, 0.0, 5.0); /* idle: output held */
    CHECK(!l.t.gains_found);
    CHECK_NEAR(l.s.out, 0.1, 1e-12);
}

static void test_tune_type1_and_abort(void)
{
    loop_t l;
    loop_init(&l);
    l.t.active = true;
    l.t.start = true;
    l.t.type = 1;
    l.t.cycles = 2;
    l.t.effort = 2.0;
    l.g.kd = 0.25;
    for (int i = 0; i < 3; i++)
        step(&l, 0.0, 1.0); /* enter, idle, start */
    step(&l, 0.0, 1.0);     /* e = -1 < 0: first switch, peak 1 */
    CHECK_NEAR(l.s.out, -2.0, 1e-12);
    step(&l, 0.0, -3.0); /* e = 3: second switch, peak 3 */
    CHECK(!l.t.start);
    CHECK_NEAR(l.t.ku, 4.0 * 2.0 / (PID_PI * 2.0), 1e-12);
    CHECK_NEAR(l.t.pu, 0.002, 1e-12);
    CHECK_NEAR(l.g.kp, 0.45 * l.t.ku, 1e-12);
    CHECK_NEAR(l.g.ki, 0.45 * l.t.ku * 1.2 / 0.002, 1e-9);
    CHECK_NEAR(l.g.ff1, 1.0, 0.0);
    CHECK_NEAR(l.g.kd, 0.0, 0.0);

    /* enable dropping while tuning aborts: output bias, tune-start cleared */
    l.t.start = true;
    step(&l, 0.0, 1.0);
    step(&l, 0.0, 1.0);
    l.in.on = false;
    l.g.offset = 0.3;
    step(&l, 0.0, 1.0);
    CHECK(!l.t.start);
    CHECK_NEAR(l.s.out, 0.3, 0.0);
    /* leaving tune mode: back to the loop after one held period */
    l.in.on = true;
    l.t.active = false;
    step(&l, 0.0, 1.0);
    CHECK(l.t.mode == PID_MODE_LOOP);
    step(&l, 0.0, 1.0);
    CHECK_NEAR(l.s.out, 0.3 + 0.45 * l.t.ku * -1.0 + l.g.ki * -0.001 + 1.0 * 0.0, 1e-9);
}

int main(void)
{
    RUN(test_proportional_and_previous_target);
    RUN(test_maxerror_then_deadband);
    RUN(test_integrator_holds_at_the_limit);
    RUN(test_maxerror_i);
    RUN(test_derivatives_and_feed_forward);
    RUN(test_index_enable_falling_edge);
    RUN(test_connected_derivative_pins);
    RUN(test_nan_error_does_not_integrate);
    RUN(test_tune_type0);
    RUN(test_tune_type1_and_abort);
    return check_summary();
}
