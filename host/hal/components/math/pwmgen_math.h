/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pwmgen_math.h - the pulse maker of the pwmgen component (docs/pwmgen.md),
 * apart from its HAL pins so it can be unit-tested on its own.  Same
 * arithmetic as LinuxCNC 2.9's software pwmgen, so the same inputs give the
 * same pulses period by period (tests/hal/pwmgen-* compare with LinuxCNC's
 * recorded output).
 *
 * update (pwm_update) turns the value into a duty cycle and a high time:
 * duty = value / scale + offset, limited to [min-dc, max-dc] in magnitude
 * (negative only for pwm+dir and up/down outputs), and chooses the mode:
 * disabled, pure PWM (the PWM period a whole number of make-pulses periods,
 * the high time rounded to whole periods, so pwm-freq and curr-dc show the
 * rounded values), dithered PWM (period and high time in ns, the rounding
 * error carried from one PWM period to the next) or PDM (pwm-freq 0: an
 * accumulator adds the high time every period, high while it is positive).
 * make-pulses (pwm_make_pulses) runs the chosen mode every fast period.
 *
 * The ns counters are 32-bit and wrap as 2.9's do; a double that does not
 * fit an int (NaN, inf) converts to INT_MIN as on x86, so NaN and infinite
 * inputs give 2.9's outputs too.  Until make-pulses has run once its period
 * is taken as -1 ns, as 2.9 does (an update that runs first sees pwm-freq
 * clamped to -5e8 and then 0).
 */
#ifndef HM_PWMGEN_MATH_H
#define HM_PWMGEN_MATH_H

#include <limits.h>
#include <stdbool.h>
#include <stdint.h>

enum { PWM_DISABLED, PWM_PURE, PWM_DITHER, PWM_PDM };

/* The make-pulses period before make-pulses has run. */
#define PWM_NO_PERIOD (-1L)

typedef struct {
    int mode;
    int32_t period;        /* PWM period, ns (PDM: the make-pulses period) */
    int32_t periods;       /* pure PWM: make-pulses periods per PWM period */
    double periods_recip;
    int32_t high_time;     /* ns high per PWM period (PDM: per make-pulses period) */
    int32_t period_timer;  /* ns into the PWM period */
    int32_t high_timer;    /* ns high so far (dither, PDM: high time owed) */
    bool out;              /* pulse output */
    bool direction;        /* negative duty cycle */
    double old_freq, old_scale, scale_recip;
    long old_periodns;
    double curr_dc;
} pwm_t;

/* The IO pins update may correct (written back as 2.9 does). */
typedef struct {
    double freq, max_dc, min_dc, scale;
} pwm_settings_t;

static inline void pwm_init(pwm_t *p)
{
    *p = (pwm_t){0};
    p->mode = PWM_DISABLED;
    p->old_scale = 2.0; /* 2.9 starts here: position-scale 2 set before the first update keeps scale_recip 0 */
    p->scale_recip = 0.0;
}

/* double -> int as x86's cvttsd2si: INT_MIN when it does not fit. */
static inline int32_t pwm_to_int(double x)
{
    if (!(x > -2147483649.0 && x < 2147483648.0))
        return INT32_MIN;
    return (int32_t)x;
}

static inline int32_t pwm_wrap(int64_t x)
{
    return (int32_t)(uint32_t)(uint64_t)x;
}

static inline void pwm_make_pulses(pwm_t *p, long periodns)
{
    int32_t dt = pwm_wrap(periodns);
    switch (p->mode) {
    case PWM_PURE:
        if (p->out) {
            p->high_timer = pwm_wrap((int64_t)p->high_timer + dt);
            if (p->high_timer >= p->high_time)
                p->out = false;
        }
        p->period_timer = pwm_wrap((int64_t)p->period_timer + dt);
        if (p->period_timer >= p->period) {
            p->period_timer = 0;
            p->high_timer = 0;
            if (p->high_time > 0)
                p->out = true;
        }
        break;
    case PWM_DITHER:
        if (p->out) {
            p->high_timer = pwm_wrap((int64_t)p->high_timer - dt);
            if (p->high_timer <= 0)
                p->out = false;
        }
        p->period_timer = pwm_wrap((int64_t)p->period_timer + dt);
        if (p->period_timer >= p->period) {
            p->period_timer = pwm_wrap((int64_t)p->period_timer - p->period);
            p->high_timer = pwm_wrap((int64_t)p->high_timer + p->high_time);
            if (p->high_timer > 0)
                p->out = true;
        }
        break;
    case PWM_PDM:
        p->high_timer = pwm_wrap((int64_t)p->high_timer + p->high_time);
        if (p->out)
            p->high_timer = pwm_wrap((int64_t)p->high_timer - dt);
        p->out = p->high_timer > 0;
        break;
    default:
        p->out = false;
        p->high_timer = 0;
        p->period_timer = 0;
        break;
    }
}

/* Period and frequency for a new mode or pwm-freq. */
static inline void pwm_set_freq(pwm_t *p, int mode, double *freq, long periodns)
{
    if (*freq <= 0.0) {
        *freq = 0.0;
        p->period = pwm_wrap(periodns);
        return;
    }
    if (*freq < 0.5)
        *freq = 0.5;
    else if (*freq > (1.0e9 / 2.0) / (double)periodns)
        *freq = (1.0e9 / 2.0) / (double)periodns;
    if (mode == PWM_PURE) {
        p->periods = pwm_to_int((1.0e9 / *freq) / (double)periodns + 0.5);
        p->periods_recip = 1.0 / p->periods;
        p->period = pwm_wrap((int64_t)p->periods * periodns);
        *freq = 1.0e9 / p->period;
    } else {
        p->period = pwm_to_int(1.0e9 / *freq);
    }
}

/*
 * One update: `s` holds pwm-freq, max-dc, min-dc and scale, corrected in
 * place; `bipolar` is false for output type 0 (negative duty cycles become
 * 0).  Sets p->curr_dc and p->direction.
 */
static inline void pwm_update(pwm_t *p, long periodns, pwm_settings_t *s, double value,
                              double offset, bool enable, bool dither, bool bipolar)
{
    if (s->max_dc > 1.0)
        s->max_dc = 1.0;
    if (s->min_dc > s->max_dc)
        s->min_dc = s->max_dc;
    if (s->min_dc < 0.0)
        s->min_dc = 0.0;
    if (s->max_dc < s->min_dc)
        s->max_dc = s->min_dc;
    if (s->scale != p->old_scale) {
        p->old_scale = s->scale;
        if (s->scale < 1e-20 && s->scale > -1e-20)
            s->scale = 1.0;
        p->scale_recip = 1.0 / s->scale;
    }
    int mode;
    if (!enable)
        mode = PWM_DISABLED;
    else if (s->freq == 0.0)
        mode = PWM_PDM;
    else if (dither)
        mode = PWM_DITHER;
    else
        mode = PWM_PURE;
    if (periodns != p->old_periodns) {
        p->old_freq = -1.0;
        p->old_periodns = periodns;
    }
    if (p->mode != mode || s->freq != p->old_freq) {
        p->mode = PWM_DISABLED;
        pwm_set_freq(p, mode, &s->freq, periodns);
        p->old_freq = s->freq;
    }
    double dc = value * p->scale_recip + offset;
    if (!bipolar && dc < 0.0)
        dc = 0.0;
    double mag;
    if (dc >= 0.0) {
        if (dc > s->max_dc)
            dc = s->max_dc;
        else if (dc < s->min_dc)
            dc = s->min_dc;
        p->direction = false;
        mag = dc;
    } else {
        /* also NaN: direction set, a high time of INT_MIN */
        if (dc < -s->max_dc)
            dc = -s->max_dc;
        else if (dc > -s->min_dc)
            dc = -s->min_dc;
        p->direction = true;
        mag = -dc;
    }
    if (mode == PWM_PURE) {
        int32_t high_periods = pwm_to_int(p->periods * mag + 0.5);
        p->high_time = pwm_wrap((int64_t)high_periods * periodns);
        if (dc >= 0.0)
            p->curr_dc = high_periods * p->periods_recip;
        else
            p->curr_dc = pwm_wrap(-(int64_t)high_periods) * p->periods_recip;
    } else {
        p->high_time = pwm_to_int(p->period * mag + 0.5);
        p->curr_dc = dc;
    }
    p->mode = mode;
}

#endif /* HM_PWMGEN_MATH_H */
