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

/* What make-pulses uses, kept small: the component keeps these of all
 * channels together, so a make-pulses call touches few cache lines. */
typedef struct {
    int32_t period;        /* PWM period, ns (PDM: the make-pulses period) */
    int32_t high_time;     /* ns high per PWM period (PDM: per make-pulses period) */
    int32_t period_timer;  /* ns into the PWM period */
    int32_t high_timer;    /* ns high so far (dither, PDM: high time owed) */
    uint8_t mode;
    bool out;              /* pulse output */
    bool direction;        /* negative duty cycle */
} pwm_pulse_t;

/* What update keeps besides. */
typedef struct {
    int32_t periods;       /* pure PWM: make-pulses periods per PWM period */
    double periods_recip;
    double old_freq, old_scale, scale_recip;
    long old_periodns;
    double curr_dc;
} pwm_t;

/* The IO pins update may correct (written back as 2.9 does). */
typedef struct {
    double freq, max_dc, min_dc, scale;
} pwm_settings_t;

static inline void pwm_init(pwm_t *p, pwm_pulse_t *q)
{
    *p = (pwm_t){0};
    *q = (pwm_pulse_t){0};
    q->mode = PWM_DISABLED;
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

/* One make-pulses period.  Written without branches on the pulse state
 * (the output changes at irregular times, a branch on it is mispredicted
 * often); the same steps as 2.9's. */
static inline void pwm_make_pulses(pwm_pulse_t *p, long periodns)
{
    uint32_t dt = (uint32_t)periodns;
    uint32_t if_out = p->out ? dt : 0u;
    switch (p->mode) {
    case PWM_PURE: {
        /* while high, count the high time; at the end of the PWM period
         * start the next one (high unless the high time is 0) */
        int32_t ht = (int32_t)((uint32_t)p->high_timer + if_out);
        bool out = p->out && ht < p->high_time;
        int32_t pt = (int32_t)((uint32_t)p->period_timer + dt);
        bool next = pt >= p->period;
        p->period_timer = next ? 0 : pt;
        p->high_timer = next ? 0 : ht;
        p->out = out | (next & (p->high_time > 0));
        break;
    }
    case PWM_DITHER: {
        /* while high, pay off the high time owed; each PWM period adds
         * high-time ns to it (the rounding carries over) */
        int32_t ht = (int32_t)((uint32_t)p->high_timer - if_out);
        bool out = p->out && ht > 0;
        int32_t pt = (int32_t)((uint32_t)p->period_timer + dt);
        bool next = pt >= p->period;
        int32_t owed = (int32_t)((uint32_t)ht + (uint32_t)p->high_time);
        p->period_timer = next ? (int32_t)((uint32_t)pt - (uint32_t)p->period) : pt;
        p->high_timer = next ? owed : ht;
        p->out = out | (next & (owed > 0));
        break;
    }
    case PWM_PDM: {
        /* add the high time of one period, take a period off when high */
        int32_t acc = (int32_t)((uint32_t)p->high_timer + (uint32_t)p->high_time - if_out);
        p->high_timer = acc;
        p->out = acc > 0;
        break;
    }
    default:
        p->out = false;
        p->high_timer = 0;
        p->period_timer = 0;
        break;
    }
}

/* Period and frequency for a new mode or pwm-freq. */
static inline void pwm_set_freq(pwm_t *p, pwm_pulse_t *q, int mode, double *freq, long periodns)
{
    if (*freq <= 0.0) {
        *freq = 0.0;
        q->period = pwm_wrap(periodns);
        return;
    }
    if (*freq < 0.5)
        *freq = 0.5;
    else if (*freq > (1.0e9 / 2.0) / (double)periodns)
        *freq = (1.0e9 / 2.0) / (double)periodns;
    if (mode == PWM_PURE) {
        p->periods = pwm_to_int((1.0e9 / *freq) / (double)periodns + 0.5);
        p->periods_recip = 1.0 / p->periods;
        q->period = pwm_wrap((int64_t)p->periods * periodns);
        *freq = 1.0e9 / q->period;
    } else {
        q->period = pwm_to_int(1.0e9 / *freq);
    }
}

/*
 * One update: `s` holds pwm-freq, max-dc, min-dc and scale, corrected in
 * place; `bipolar` is false for output type 0 (negative duty cycles become
 * 0).  Sets p->curr_dc and q->direction.
 */
static inline void pwm_update(pwm_t *p, pwm_pulse_t *q, long periodns, pwm_settings_t *s,
                              double value, double offset, bool enable, bool dither,
                              bool bipolar)
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
    if (q->mode != mode || s->freq != p->old_freq) {
        q->mode = PWM_DISABLED;
        pwm_set_freq(p, q, mode, &s->freq, periodns);
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
        q->direction = false;
        mag = dc;
    } else {
        /* also NaN: direction set, a high time of INT_MIN */
        if (dc < -s->max_dc)
            dc = -s->max_dc;
        else if (dc > -s->min_dc)
            dc = -s->min_dc;
        q->direction = true;
        mag = -dc;
    }
    if (mode == PWM_PURE) {
        int32_t high_periods = pwm_to_int(p->periods * mag + 0.5);
        q->high_time = pwm_wrap((int64_t)high_periods * periodns);
        if (dc >= 0.0)
            p->curr_dc = high_periods * p->periods_recip;
        else
            p->curr_dc = pwm_wrap(-(int64_t)high_periods) * p->periods_recip;
    } else {
        q->high_time = pwm_to_int(q->period * mag + 0.5);
        p->curr_dc = dc;
    }
    q->mode = mode;
}

#endif /* HM_PWMGEN_MATH_H */
