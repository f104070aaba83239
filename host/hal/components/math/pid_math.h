/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pid_math.h - the arithmetic of the pid component (docs/pid.md), apart
 * from its HAL pins so it can be unit-tested on its own.
 *
 * One call of pid_calc() is one period of LinuxCNC 2.9's pid: the same
 * operations in the same order, so the same inputs give the same doubles
 * (checked against LinuxCNC's recorded output in tests/hal/pid-*):
 *
 *   error     = (error-previous-target ? previous command : command) - feedback
 *               (the current command right after a falling index-enable)
 *   e         = error limited to +-maxerror, then moved towards 0 by deadband
 *   errorI   += e * period, unless the output was clamped at the limit on the
 *               side e pushes towards; then limited to +-maxerrorI
 *   commandD  = command-deriv if connected, else (command - previous) / period,
 *               held on a falling index-enable; limited to +-maxcmdD
 *   commandDD, commandDDD: differences of the limited lower derivative
 *   errorD    = (unlimited commandD) - (feedback-deriv or its estimate),
 *               limited to +-maxerrorD
 *   output    = (bias + P e + I errorI + D errorD)
 *             + (FF0 command + FF1 commandD + FF2 commandDD + FF3 commandDDD)
 *               limited to +-maxoutput
 *
 * A limit of 0 means "no limit".  While disabled the derivatives are still
 * tracked, but errorI, output and the saturation state are zero.
 *
 * pid_step() adds LinuxCNC 2.9's relay auto-tuner (tune-mode, Astrom and
 * Hagglund's relay method): while tune-mode is true the loop is not run;
 * after tune-start the output switches between bias+effort and
 * bias-effort on the sign of command - feedback, and after tune-cycles
 * switches
 *   amplitude       = sum over half-cycles of the largest |error| / cycles
 *   ultimate-gain   = 4 effort / (pi amplitude)
 *   ultimate-period = time since the start / (cycles / 2)
 * and the gains are set by Ziegler-Nichols: tune-type 0 P = 0.6 Ku,
 * I = 2 P / Pu, D = P Pu / 8, FF1 = 0; otherwise P = 0.45 Ku,
 * I = 1.2 P / Pu, D = 0, FF1 = 1.
 */
#ifndef HM_PID_MATH_H
#define HM_PID_MATH_H

#include <math.h>
#include <stdbool.h>

#define PID_PI 3.14159265358979323846

/* Field names differ from the pin names on purpose: in a .comp every pin
 * name is a macro. */
typedef struct {
    double kp, ki, kd, offset;                  /* Pgain Igain Dgain bias */
    double ff0, ff1, ff2, ff3;                  /* FF0 .. FF3 */
    double db;                                  /* deadband */
    double lim_err, lim_err_i, lim_err_d;       /* maxerror maxerrorI maxerrorD */
    double lim_cmd_d, lim_cmd_dd, lim_cmd_ddd;  /* maxcmdD maxcmdDD maxcmdDDD */
    double lim_out;                             /* maxoutput */
} pid_gains_t;

typedef struct {
    double cmd, fb;                 /* command feedback */
    double cmd_d_in, fb_d_in;       /* command-deriv feedback-deriv, */
    bool cmd_d_given, fb_d_given;   /* used when connected to a signal */
    bool on, index, prev_target;    /* enable index-enable error-previous-target */
} pid_inputs_t;

typedef struct {
    /* results, published on pins */
    double out, err;                        /* output error */
    double err_i, err_d;                    /* errorI errorD */
    double cmd_d, cmd_dd, cmd_ddd;          /* commandD commandDD commandDDD */
    double sat_s;                           /* saturated-s */
    int sat_count;                          /* saturated-count */
    bool sat;                               /* saturated */
    /* memory between periods */
    double prev_cmd, prev_fb;
    double raw_cmd_d; /* commandD before maxcmdD: feeds errorD */
    double fb_d;
    int limit_state; /* +1 / -1: output clamped at +/-maxoutput, 0 not */
    bool prev_index;
} pid_state_t;

typedef enum {
    PID_MODE_LOOP,   /* normal PID */
    PID_MODE_IDLE,   /* tune-mode, waiting for tune-start */
    PID_MODE_START,  /* first relay period */
    PID_MODE_POS,    /* relay at bias + effort */
    PID_MODE_NEG,    /* relay at bias - effort */
} pid_mode_t;

typedef struct {
    /* inputs */
    bool active;             /* tune-mode */
    unsigned type, cycles;   /* tune-type tune-cycles */
    double effort;           /* tune-effort */
    bool start;              /* tune-start (I/O): cleared when tuning ends */
    /* results */
    double ku, pu;           /* ultimate-gain ultimate-period */
    bool gains_found;        /* this period's pid_step() wrote new gains */
    /* memory */
    pid_mode_t mode;
    double elapsed, amp_sum, peak;
    unsigned half_cycles;
} pid_tune_t;

/* x limited to +-lim; lim == 0 means no limit.  A NaN x passes. */
static inline double pid_limit(double x, double lim)
{
    if (lim != 0.0) {
        if (x > lim)
            return lim;
        if (x < -lim)
            return -lim;
    }
    return x;
}

/* error limited by maxerror, then the deadband taken off (inside it: 0). */
static inline double pid_effective_error(double error, const pid_gains_t *g)
{
    double e = pid_limit(error, g->lim_err);
    if (e > g->db)
        return e - g->db;
    if (e < -g->db)
        return e + g->db;
    return 0.0;
}

/* Command and feedback derivatives for this period (updates the state). */
static inline void pid_derivatives(pid_state_t *s, const pid_inputs_t *in, const pid_gains_t *g,
                                   double rate, bool index_fell)
{
    double cd;
    if (in->cmd_d_given)
        cd = in->cmd_d_in;
    else if (index_fell)
        cd = s->raw_cmd_d;
    else
        cd = (in->cmd - s->prev_cmd) * rate;
    s->raw_cmd_d = cd;
    cd = pid_limit(cd, g->lim_cmd_d);
    double cdd = pid_limit((cd - s->cmd_d) * rate, g->lim_cmd_dd);
    double cddd = pid_limit((cdd - s->cmd_dd) * rate, g->lim_cmd_ddd);
    s->cmd_d = cd;
    s->cmd_dd = cdd;
    s->cmd_ddd = cddd;

    if (in->fb_d_given)
        s->fb_d = in->fb_d_in;
    else if (!index_fell)
        s->fb_d = (in->fb - s->prev_fb) * rate;
    s->err_d = pid_limit(s->raw_cmd_d - s->fb_d, g->lim_err_d);
}

/* Output limiting.  With maxoutput 0 nothing is clamped and the clamp
 * state is left as it was (LinuxCNC 2.9). */
static inline void pid_clamp(pid_state_t *s, const pid_gains_t *g)
{
    if (g->lim_out == 0.0)
        return;
    if (s->out > g->lim_out) {
        s->out = g->lim_out;
        s->limit_state = 1;
    } else if (s->out < -g->lim_out) {
        s->out = -g->lim_out;
        s->limit_state = -1;
    } else {
        s->limit_state = 0;
    }
}

/* How long the output has been saturated. */
static inline void pid_saturation_time(pid_state_t *s, double period_s)
{
    s->sat = s->limit_state != 0;
    if (s->sat) {
        s->sat_s += period_s;
        s->sat_count++;
    } else {
        s->sat_s = 0.0;
        s->sat_count = 0;
    }
}

/* One period of the PID loop.  period_ns > 0. */
static inline void pid_calc(pid_state_t *s, const pid_inputs_t *in, const pid_gains_t *g,
                            long period_ns)
{
    double period_s = period_ns * 0.000000001;
    double rate = 1.0 / period_s;
    bool index_fell = s->prev_index && !in->index;
    s->prev_index = in->index;

    if (in->prev_target && !index_fell)
        s->err = s->prev_cmd - in->fb;
    else
        s->err = in->cmd - in->fb;
    double e = pid_effective_error(s->err, g);

    if (in->on) {
        /* no integration towards the side the output is clamped at
         * (written so that a NaN product integrates nothing, as 2.9) */
        if (s->limit_state * e <= 0.0)
            s->err_i += e * period_s;
        s->err_i = pid_limit(s->err_i, g->lim_err_i);
    } else {
        s->err_i = 0.0;
    }

    pid_derivatives(s, in, g, rate, index_fell);
    s->prev_cmd = in->cmd;
    s->prev_fb = in->fb;

    if (in->on) {
        double pid = g->offset + g->kp * e + g->ki * s->err_i + g->kd * s->err_d;
        double ff = g->ff0 * in->cmd + g->ff1 * s->cmd_d + g->ff2 * s->cmd_dd +
                    g->ff3 * s->cmd_ddd;
        s->out = pid + ff;
        pid_clamp(s, g);
    } else {
        s->out = 0.0;
        s->limit_state = 0;
    }
    pid_saturation_time(s, period_s);
}

/* Ziegler-Nichols gains from the measured ultimate gain and period. */
static inline void pid_tune_finish(pid_tune_t *t, pid_gains_t *g)
{
    double cycles = t->cycles;
    double amplitude = t->amp_sum / cycles;
    t->ku = 4.0 * t->effort / (PID_PI * amplitude);
    t->pu = t->elapsed / (cycles / 2.0);
    t->gains_found = true;
    if (t->type == 0) {
        g->kp = 0.6 * t->ku;
        g->ki = 2 * g->kp / t->pu;
        g->kd = g->kp * t->pu / 8;
        g->ff1 = 0.0;
    } else {
        g->kp = 0.45 * t->ku;
        g->ki = g->kp * 1.2 / t->pu;
        g->ff1 = 1.0;
        g->kd = 0.0;
    }
}

/* One period of the relay (modes other than PID_MODE_LOOP). */
static inline void pid_tune_relay(pid_state_t *s, pid_tune_t *t, const pid_inputs_t *in,
                                  pid_gains_t *g, double period_s)
{
    s->err = in->cmd - in->fb;
    if (!t->active || !in->on) {
        s->out = g->offset;
        t->start = false;
        t->mode = t->active ? PID_MODE_IDLE : PID_MODE_LOOP;
        return;
    }
    switch (t->mode) {
    case PID_MODE_IDLE:
        if (t->start)
            t->mode = PID_MODE_START;
        return;
    case PID_MODE_START:
        s->out = g->offset + t->effort;
        t->mode = PID_MODE_POS;
        t->elapsed = 0.0;
        t->amp_sum = 0.0;
        t->peak = 0.0;
        t->half_cycles = 0;
        return;
    default:
        break;
    }
    t->elapsed += period_s;
    if (fabs(s->err) > t->peak)
        t->peak = fabs(s->err);
    bool flip = t->mode == PID_MODE_POS ? s->err < 0.0 : s->err > 0.0;
    if (flip) {
        t->amp_sum += t->peak;
        t->peak = 0.0;
        t->half_cycles++;
        t->mode = t->mode == PID_MODE_POS ? PID_MODE_NEG : PID_MODE_POS;
        if (t->half_cycles >= t->cycles) {
            pid_tune_finish(t, g);
            s->out = g->offset;
            t->start = false;
            t->mode = PID_MODE_IDLE;
            return;
        }
    }
    s->out = t->mode == PID_MODE_POS ? g->offset + t->effort : g->offset - t->effort;
}

/* Entering tune-mode from the loop: the output and the loop's internal
 * values drop to zero; the saturation report and the feedback history
 * stay as they were (LinuxCNC 2.9). */
static inline void pid_tune_enter(pid_state_t *s, pid_tune_t *t, const pid_inputs_t *in)
{
    bool index_fell = s->prev_index && !in->index;
    s->prev_index = in->index;
    if (in->prev_target && !index_fell)
        s->err = s->prev_cmd - in->fb;
    else
        s->err = in->cmd - in->fb;
    s->out = 0.0;
    s->err_i = 0.0;
    s->err_d = 0.0;
    s->cmd_d = 0.0;
    s->cmd_dd = 0.0;
    s->cmd_ddd = 0.0;
    s->prev_cmd = 0.0;
    s->limit_state = 0;
    t->mode = PID_MODE_IDLE;
}

/* One period of pid with its auto-tuner.  The tuner writes the gains it
 * finds into *g (the caller publishes them on the gain pins). */
static inline void pid_step(pid_state_t *s, pid_tune_t *t, const pid_inputs_t *in,
                            pid_gains_t *g, long period_ns)
{
    t->gains_found = false;
    if (t->mode != PID_MODE_LOOP)
        pid_tune_relay(s, t, in, g, period_ns * 0.000000001);
    else if (t->active)
        pid_tune_enter(s, t, in);
    else
        pid_calc(s, in, g, period_ns);
}

#endif /* HM_PID_MATH_H */
