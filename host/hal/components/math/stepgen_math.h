/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * stepgen_math.h - the step generator of the stepgen component
 * (docs/stepgen.md), apart from its HAL pins so it can be unit-tested on
 * its own.  Same arithmetic as LinuxCNC 2.9's software stepgen, so the same
 * inputs give the same steps, positions and frequencies (tests/hal/stepgen-*
 * compare with LinuxCNC's recorded output).
 *
 * Position is a 64-bit fixed-point accumulator with SG_FRAC_BITS fraction
 * bits, in steps, offset by half a step so that a step happens when the
 * position crosses n + 1/2.  make-pulses (sg_make_pulses) adds `addval` to
 * it every period, after moving addval towards the target that
 * update-freq (sg_update_freq) computed, by at most `deltalim`; a change of
 * the integer part is a step.  update-freq turns the velocity command, or
 * the position command through a small position loop, into a frequency
 * limited by maxvel and maxaccel and by what the timing parameters allow.
 *
 * Timing (ns, rounded up to whole make-pulses periods): a step starts
 * three timers: t1 = steplen (the step pulse), t2 = t1 + dirhold (type 0)
 * until the direction output may change, t3 = t2 + dirsetup (type 0) or
 * steplen + dirdelay (other types) until a step the other way may follow.
 * When the velocity changes sign while t3 runs, the generator freezes
 * (no motion, the new velocity kept) until t3 expires; the direction
 * output follows the frozen velocity once t2 has expired.
 */
#ifndef HM_STEPGEN_MATH_H
#define HM_STEPGEN_MATH_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

#define SG_FRAC_BITS 28
#define SG_ONE_STEP (INT64_C(1) << SG_FRAC_BITS)
#define SG_HALF_STEP (INT64_C(1) << (SG_FRAC_BITS - 1))
#define SG_MAX_PHASES 5
#define SG_USER_STEPS 18 /* longest user_step_type table (LinuxCNC 2.9) */
#define SG_USER_TYPE 15
#define SG_DEFAULT_PERIOD_NS 50000L /* until make-pulses has run */

/* Output patterns of step types 2..14, one entry per state, bit 0 = phase
 * A ... bit 4 = phase E; forward motion walks the table upwards.  Recorded
 * from LinuxCNC 2.9 (tests/hal/stepgen-phases). */
typedef struct {
    unsigned char len, phases;
    unsigned char state[10];
} sg_pattern_t;

static const sg_pattern_t sg_patterns[15] = {
    [2] = {4, 2, {1, 3, 2, 0}},
    [3] = {3, 3, {1, 2, 4}},
    [4] = {6, 3, {1, 3, 2, 6, 4, 5}},
    [5] = {4, 4, {1, 2, 4, 8}},
    [6] = {4, 4, {3, 6, 12, 9}},
    [7] = {4, 4, {1, 7, 14, 8}},
    [8] = {4, 4, {5, 6, 10, 9}},
    [9] = {8, 4, {1, 3, 2, 6, 4, 12, 8, 9}},
    [10] = {8, 4, {1, 5, 7, 6, 14, 10, 8, 9}},
    [11] = {5, 5, {1, 2, 4, 8, 16}},
    [12] = {5, 5, {3, 6, 12, 24, 17}},
    [13] = {10, 5, {1, 3, 2, 6, 4, 12, 8, 24, 16, 17}},
    [14] = {10, 5, {3, 7, 6, 14, 12, 28, 24, 25, 17, 19}},
};

/* Output bits of step types 0 and 1 (in sg_chan_t.out). */
#define SG_OUT_STEP 1u /* type 0 step, type 1 up */
#define SG_OUT_DIR 2u  /* type 0 dir, type 1 down */

typedef struct {
    /* configuration, fixed at load */
    int type;           /* 0 .. 15 */
    bool pos_mode;      /* ctrl_type p */
    int table_len;      /* states of types 2..15 */
    unsigned char table[SG_USER_STEPS];

    /* parameters (published as HAL parameters, user-writable) */
    uint32_t steplen, stepspace, dirsetup, dirhold, dirdelay; /* ns */
    double maxvel, maxaccel, scale;
    /* published */
    double freq;        /* steps/s (parameter "frequency") */
    int32_t rawcount;   /* parameter "rawcounts" */
    unsigned out;       /* output bits (types 0/1: SG_OUT_*, others: phases) */

    /* step generator state */
    int64_t accum, addval, target_addval, deltalim;
    long t1, t2, t3;    /* ns left: step pulse, dir hold, reverse step */
    bool frozen;        /* waiting for t3 before reversing */
    int state;          /* index into table */

    /* update-freq state */
    double old_pos_cmd, old_scale, scale_recip;
    bool too_fast_reported; /* the maxvel message is printed once */
} sg_chan_t;

/* The module-wide timing both functions share. */
typedef struct {
    long make_period; /* ns, the period make-pulses last ran with */
    long last_period; /* the make_period update-freq last saw */
    long servo_period;
    double recip_dt;  /* 1 / update-freq period in s */
    double freqscale, accelscale;
} sg_timebase_t;

static inline void sg_timebase_init(sg_timebase_t *tb)
{
    tb->make_period = SG_DEFAULT_PERIOD_NS;
    tb->last_period = 0;
    tb->servo_period = 0;
    tb->recip_dt = 0.0;
    tb->freqscale = tb->accelscale = 0.0;
}

/* A channel of step type `type` (0..15; 15 uses user[0..user_len-1]). */
static inline void sg_chan_init(sg_chan_t *c, int type, bool pos_mode, const int *user,
                                int user_len)
{
    *c = (sg_chan_t){0};
    c->type = type;
    c->pos_mode = pos_mode;
    if (type == SG_USER_TYPE) {
        c->table_len = user_len;
        for (int i = 0; i < user_len; i++)
            c->table[i] = (unsigned char)user[i];
    } else if (type >= 2) {
        c->table_len = sg_patterns[type].len;
        for (int i = 0; i < c->table_len; i++)
            c->table[i] = sg_patterns[type].state[i];
    }
    c->steplen = c->stepspace = c->dirsetup = c->dirhold = c->dirdelay = 1;
    c->scale = 1.0;
    c->old_scale = 0.0;
    c->scale_recip = 1.0 / SG_ONE_STEP;
    c->accum = SG_HALF_STEP;
    c->out = c->table_len ? c->table[0] : 0;
}

/* Phases a user table needs (highest bit set + 1), or -1 if a value uses
 * more than five. */
static inline int sg_user_phases(const int *user, int len)
{
    int bits = 0;
    for (int i = 0; i < len; i++) {
        if (user[i] < 0 || user[i] >= (1 << SG_MAX_PHASES))
            return -1;
        bits |= user[i];
    }
    int n = 0;
    while (bits >> n)
        n++;
    return n;
}

/* ---- make-pulses --------------------------------------------------- */

static inline long sg_countdown(long t, long period)
{
    return t > period ? t - period : 0;
}

static inline int64_t sg_ramp(int64_t from, int64_t to, int64_t lim)
{
    if (lim != 0) {
        if (to > from + lim)
            return from + lim;
        if (to < from - lim)
            return from - lim;
    }
    return to;
}

/* Direction output (type 0) from the sign of a velocity; 0 keeps it. */
static inline void sg_set_dir(sg_chan_t *c, int64_t v)
{
    if (c->type != 0)
        return;
    if (v > 0)
        c->out &= ~SG_OUT_DIR;
    else if (v < 0)
        c->out |= SG_OUT_DIR;
}

static inline void sg_take_step(sg_chan_t *c, bool up)
{
    c->t1 = c->steplen;
    if (c->type == 0) {
        c->t2 = c->t1 + c->dirhold;
        c->t3 = c->t2 + c->dirsetup;
        c->out |= SG_OUT_STEP;
    } else {
        c->t2 = c->t1;
        c->t3 = c->t1 + c->dirdelay;
        if (c->type == 1) {
            c->out |= up ? SG_OUT_STEP : SG_OUT_DIR;
        } else if (c->table_len) {
            c->state = up ? (c->state + 1 == c->table_len ? 0 : c->state + 1)
                          : (c->state == 0 ? c->table_len - 1 : c->state - 1);
            c->out = c->table[c->state];
        }
    }
}

/* One make-pulses period of one channel.  period_ns > 0. */
static inline void sg_make_pulses(sg_chan_t *c, bool enable, long period_ns)
{
    c->t1 = sg_countdown(c->t1, period_ns);
    c->t2 = sg_countdown(c->t2, period_ns);
    c->t3 = sg_countdown(c->t3, period_ns);
    if (c->t1 == 0 && c->type <= 1)
        c->out &= c->type == 0 ? ~SG_OUT_STEP : 0u;
    if (!enable)
        return;
    if (c->frozen) {
        if (c->t2 == 0)
            sg_set_dir(c, c->addval);
        if (c->t3 != 0)
            return;
        c->frozen = false;
    }
    int64_t old = c->addval;
    int64_t v = sg_ramp(old, c->target_addval, c->deltalim);
    c->addval = v;
    if ((old >= 0) != (v >= 0) && c->t3 != 0) {
        /* reversing too soon after a step: freeze until t3 expires */
        c->frozen = true;
        if (c->t2 == 0)
            sg_set_dir(c, v);
        return;
    }
    sg_set_dir(c, v);
    int64_t before = c->accum >> SG_FRAC_BITS;
    c->accum += v;
    int64_t after = c->accum >> SG_FRAC_BITS;
    if (after != before)
        sg_take_step(c, after > before);
    c->rawcount = (int32_t)after;
}

/* ---- capture-position ---------------------------------------------- */

static inline void sg_check_scale(sg_chan_t *c)
{
    if (c->scale != c->old_scale) {
        c->old_scale = c->scale;
        if (c->scale < 1e-20 && c->scale > -1e-20)
            c->scale = 1.0; /* a divide by zero is a bad thing */
        c->scale_recip = (1.0 / SG_ONE_STEP) / c->scale;
    }
}

/* counts and position-fb. */
static inline void sg_capture(sg_chan_t *c, int32_t *counts, double *pos_fb)
{
    sg_check_scale(c);
    int64_t acc = c->accum;
    *counts = (int32_t)(acc >> SG_FRAC_BITS);
    *pos_fb = (double)(acc - SG_HALF_STEP) * c->scale_recip;
}

/* ---- update-freq --------------------------------------------------- */

/* x rounded up to a whole number of periods, as a u32 parameter. */
static inline uint32_t sg_round_up(uint32_t x, long period)
{
    uint64_t p = (uint64_t)period;
    uint64_t r = ((uint64_t)x + p - 1) / p * p;
    return r > UINT32_MAX ? (uint32_t)(UINT32_MAX / p * p) : (uint32_t)r;
}

/* Per update-freq call: the module-wide constants for this period. */
static inline void sg_timebase_update(sg_timebase_t *tb, long servo_period_ns)
{
    if (tb->make_period != tb->last_period) {
        double periodfp = tb->make_period * 0.000000001;
        tb->freqscale = SG_ONE_STEP * periodfp;
        tb->accelscale = tb->freqscale * periodfp;
        tb->last_period = tb->make_period;
    }
    if (servo_period_ns != tb->servo_period) {
        tb->servo_period = servo_period_ns;
        tb->recip_dt = 1.0 / (servo_period_ns * 0.000000001);
    }
}

/* Timing parameters rounded up to whole make-pulses periods.  steplen,
 * type 0's dirhold and type 1's dirdelay are at least one period; the
 * others may be 0 (LinuxCNC 2.9). */
static inline void sg_round_timing(sg_chan_t *c, long period)
{
    if (c->steplen == 0)
        c->steplen = 1;
    if (c->dirhold == 0 && c->type == 0)
        c->dirhold = 1;
    if (c->dirdelay == 0 && c->type == 1)
        c->dirdelay = 1;
    c->steplen = sg_round_up(c->steplen, period);
    c->stepspace = sg_round_up(c->stepspace, period);
    c->dirsetup = sg_round_up(c->dirsetup, period);
    c->dirhold = sg_round_up(c->dirhold, period);
    c->dirdelay = sg_round_up(c->dirdelay, period);
}

/* The fastest the timing allows and the user's maxvel / maxaccel: sets
 * *max_freq (steps/s) and *max_ac (steps/s^2); lowers a maxvel that is too
 * high (reporting it once through `too_fast(channel, want, limit)`), and
 * zeroes negative ones, as 2.9 does. */
static inline void sg_limits(sg_chan_t *c, const sg_timebase_t *tb, double *max_freq,
                             double *max_ac, int channel, void (*too_fast)(int, int, int))
{
    long min_step = c->steplen;
    if (c->type <= 1)
        min_step += c->stepspace;
    double fmax = 1.0 / (min_step * 0.000000001);
    double scale = fabs(c->scale);
    if (c->maxvel <= 0.0) {
        c->maxvel = 0.0;
    } else {
        double want = c->maxvel * scale;
        if (want > fmax) {
            if (!c->too_fast_reported && too_fast) {
                too_fast(channel, want < 2147483647.0 ? (int)want : 2147483647, (int)fmax);
                c->too_fast_reported = true;
            }
            c->maxvel = fmax / scale;
        } else {
            fmax = want;
        }
    }
    double acmax = fmax * tb->recip_dt;
    if (c->maxaccel <= 0.0) {
        c->maxaccel = 0.0;
    } else if (c->maxaccel * scale > acmax) {
        c->maxaccel = acmax / scale;
    } else {
        acmax = c->maxaccel * scale;
    }
    *max_freq = fmax;
    *max_ac = acmax;
}

/* The position loop: the next velocity (steps/s) that follows pos_cmd
 * (steps) without exceeding max_freq / max_ac. */
static inline double sg_follow(sg_chan_t *c, double pos_cmd, double max_ac, double recip_dt)
{
    double vel_cmd = (pos_cmd - c->old_pos_cmd) * recip_dt;
    c->old_pos_cmd = pos_cmd;
    double curr_pos = (double)(c->accum - SG_HALF_STEP) * (1.0 / SG_ONE_STEP);
    double curr_vel = c->freq;
    double dt = 1.0 / recip_dt;
    /* ramp towards the commanded velocity; where would that leave us? */
    double match_ac = vel_cmd > curr_vel ? max_ac : -max_ac;
    double match_time = (vel_cmd - curr_vel) / match_ac;
    double avg_v = (vel_cmd + curr_vel) * 0.5;
    double est_out = curr_pos + avg_v * match_time;
    double est_cmd = pos_cmd + vel_cmd * (match_time - 1.5 / recip_dt);
    double est_err = est_out - est_cmd;
    double v;
    if (match_time < dt) {
        /* the velocity can be matched within this period */
        if (fabs(est_err) < 0.0001) {
            v = vel_cmd;
        } else {
            v = vel_cmd - 0.5 * est_err * recip_dt;
            if (v > curr_vel + max_ac / recip_dt)
                v = curr_vel + max_ac / recip_dt;
            else if (v < curr_vel - max_ac / recip_dt)
                v = curr_vel - max_ac / recip_dt;
        }
    } else {
        /* ramping the other way for one period: does it end closer? */
        double dv = -2.0 * match_ac / recip_dt;
        double dp = dv * match_time;
        if (fabs(est_err + dp * 2.0) < fabs(est_err))
            match_ac = -match_ac;
        v = curr_vel + match_ac / recip_dt;
    }
    return v;
}

/* One update-freq period of one channel: cmd is position-cmd (position
 * mode) or velocity-cmd, in user units. */
static inline void sg_update_freq(sg_chan_t *c, const sg_timebase_t *tb, bool enable, double cmd,
                                  int channel, void (*too_fast)(int, int, int))
{
    sg_check_scale(c);
    sg_round_timing(c, tb->make_period);
    if (!enable) {
        if (c->pos_mode)
            c->old_pos_cmd = cmd * c->scale;
        c->freq = 0.0;
        c->addval = 0;
        c->target_addval = 0;
        return;
    }
    double max_freq, max_ac;
    sg_limits(c, tb, &max_freq, &max_ac, channel, too_fast);
    double v;
    if (c->pos_mode) {
        v = sg_follow(c, cmd * c->scale, max_ac, tb->recip_dt);
        if (v > max_freq)
            v = max_freq;
        else if (v < -max_freq)
            v = -max_freq;
    } else {
        double vel_cmd = cmd * c->scale;
        if (vel_cmd > max_freq)
            vel_cmd = max_freq;
        else if (vel_cmd < -max_freq)
            vel_cmd = -max_freq;
        double dv = max_ac / tb->recip_dt;
        if (vel_cmd > c->freq + dv)
            v = c->freq + dv;
        else if (vel_cmd < c->freq - dv)
            v = c->freq - dv;
        else
            v = vel_cmd;
    }
    c->freq = v;
    c->target_addval = (int64_t)(v * tb->freqscale);
    c->deltalim = (int64_t)(max_ac * tb->accelscale);
}

#endif /* HM_STEPGEN_MATH_H */
