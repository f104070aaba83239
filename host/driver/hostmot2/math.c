/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The driver's arithmetic (spec §10), kept free of HAL so it can be tested
 * against independent references. */
#include <math.h>
#include <stdint.h>

#include "hm2/hm2.h"

/* ---------------- StepGen ---------------- */

#define STEPGEN_TIMER_MAX 0x3FFFu

uint32_t hm2_stepgen_ns_to_clocks(uint32_t ns, uint32_t clock_low, bool *clipped)
{
    double clocks = floor((double)ns * (double)clock_low / 1e9);
    *clipped = clocks > STEPGEN_TIMER_MAX;
    return *clipped ? STEPGEN_TIMER_MAX : (uint32_t)clocks;
}

double hm2_stepgen_clocks_to_ns(uint32_t clocks, uint32_t clock_low)
{
    return (double)clocks * 1e9 / (double)clock_low;
}

double hm2_stepgen_physical_maxvel(uint32_t steplen_ns, uint32_t stepspace_ns, double scale)
{
    double period_ns = (double)steplen_ns + (double)stepspace_ns;
    if (period_ns <= 0.0 || scale == 0.0)
        return 0.0; /* no bound can be derived (caller treats 0 as "none") */
    return (1e9 / period_ns) / fabs(scale);
}

uint32_t hm2_stepgen_rate_register(double vel, double scale, uint32_t clock_low)
{
    double steps_per_s = vel * scale;
    double rate = steps_per_s * 4294967296.0 / (double)clock_low;
    /* The rate is a signed 32-bit number of 2^-32 steps per clock; maxvel
     * keeps it in range, the clamp only guards the conversion. */
    if (!(rate == rate))
        rate = 0.0;
    if (rate > 2147483647.0)
        rate = 2147483647.0;
    if (rate < -2147483648.0)
        rate = -2147483648.0;
    return (uint32_t)(int32_t)rate;
}

double hm2_stepgen_position_control(struct hm2_stepgen_posctl *p)
{
    const double T = p->period_s;
    double ff_vel, vel_err, match_accel, t_match, pos_at_match, cmd_at_match, err_at_match, vcmd;

    p->dbg_pos_minus_prev_cmd = p->position_fb - p->old_position_cmd;
    ff_vel = (p->position_cmd - p->old_position_cmd) / T;
    p->dbg_ff_vel = ff_vel;
    p->old_position_cmd = p->position_cmd;

    vel_err = p->velocity_fb - ff_vel;
    p->dbg_vel_error = vel_err;

    /* accelerate toward the commanded velocity at maxaccel; with maxaccel
     * 0 (no limit) LinuxCNC 2.9 uses -verr/T for verr > 0 but +verr/T for
     * verr < 0 (spec §10.1 "∓verr/T"), kept as is for identical output */
    if (vel_err > 0.0)
        match_accel = p->maxaccel == 0.0 ? -vel_err / T : -p->maxaccel;
    else if (vel_err < 0.0)
        match_accel = p->maxaccel == 0.0 ? vel_err / T : p->maxaccel;
    else
        match_accel = 0.0;

    t_match = match_accel == 0.0 ? 0.0 : -vel_err / match_accel;
    p->dbg_s_to_match = t_match;

    /* where feedback and command will be once the velocities match */
    pos_at_match = p->position_fb + (ff_vel + p->velocity_fb) * 0.5 * (t_match + T);
    cmd_at_match = p->position_cmd + ff_vel * t_match;
    err_at_match = pos_at_match - cmd_at_match;
    p->dbg_err_at_match = err_at_match;

    if (t_match < T) {
        /* velocity matches within this period: also correct the position */
        vcmd = ff_vel - 0.5 * err_at_match / T;
        if (p->maxaccel > 0.0) {
            double hi = p->velocity_fb + p->maxaccel * T;
            double lo = p->velocity_fb - p->maxaccel * T;
            if (vcmd > hi)
                vcmd = hi;
            else if (vcmd < lo)
                vcmd = lo;
        }
    } else {
        /* several periods to match: ramp, the other way if ramping
         * the other way for one period would end closer */
        double dv = -2.0 * match_accel * T;
        double dp = dv * t_match;
        if (fabs(err_at_match + 2.0 * dp) < fabs(err_at_match))
            match_accel = -match_accel;
        vcmd = p->velocity_fb + match_accel * T;
    }
    return vcmd;
}

double hm2_stepgen_velocity_control(double velocity_cmd, double velocity_fb, double maxaccel,
                                    double period_s)
{
    if (maxaccel > 0.0) {
        double dv = maxaccel * period_s;
        if (velocity_cmd > velocity_fb + dv)
            return velocity_fb + dv;
        if (velocity_cmd < velocity_fb - dv)
            return velocity_fb - dv;
    }
    return velocity_cmd;
}

int64_t hm2_stepgen_accumulate(int64_t subcounts, uint32_t prev_acc, uint32_t acc)
{
    /* The accumulator is a wrapping 16.16 number: the change since the last
     * read is the 32-bit two's-complement difference.  (LinuxCNC 2.9
     * corrects the wrap by 2^32-1; this uses the exact 2^32.) */
    int32_t delta = (int32_t)(acc - prev_acc);
    return subcounts + delta;
}

/* ---------------- Encoder ---------------- */

uint32_t hm2_encoder_tsdiv(uint32_t clock_low, bool hires)
{
    uint32_t div = clock_low / (hires ? 10000000u : 2000000u);
    return div >= 2 ? div - 2 : 0;
}

double hm2_encoder_seconds_per_tsc(uint32_t clock_low, uint32_t tsdiv)
{
    return ((double)tsdiv + 2.0) / (double)clock_low;
}

uint32_t hm2_encoder_qfilter_rate(uint32_t clock_low, uint32_t sample_frequency,
                                  uint32_t *effective_frequency)
{
    uint32_t div = sample_frequency ? clock_low / sample_frequency : 1;
    if (div <= 1) {
        *effective_frequency = clock_low;
        return 0xFFF; /* bit 11: divide by 1 */
    }
    if (div - 2 > 0x7FF)
        div = 0x7FF + 2; /* slowest rate the 11-bit divider holds */
    *effective_frequency = clock_low / div;
    return div - 2;
}

int32_t hm2_wrap16(int32_t diff)
{
    if (diff > 32768)
        diff -= 65536;
    else if (diff < -32768)
        diff += 65536;
    return diff;
}

int hm2_encoder_track_update(struct hm2_encoder_track *t, const struct hm2_encoder_sample *s,
                             double scale, double seconds_per_tsc, double vel_timeout,
                             bool *probe_event)
{
    uint16_t reg_count = (uint16_t)(s->count_reg & 0xFFFF);
    uint16_t reg_ts = (uint16_t)(s->count_reg >> 16);
    int32_t prev_rawcounts = t->rawcounts;
    int index_event = 0;

    *probe_event = false;
    /* latches: a LatchOnIndex/LatchOnProbe bit we set that reads back 0
     * means the event happened and the count sits in CCR[31:16] */
    if (t->latch_pending && !(s->ccr & (1u << 4))) {
        uint16_t latched = (uint16_t)(s->ccr >> 16);
        t->zero_offset = prev_rawcounts + hm2_wrap16((int32_t)latched - t->prev_reg_count);
        t->latch_pending = false;
        index_event = 1;
    }
    if (t->probe_pending && !(s->ccr & (1u << 13))) {
        uint16_t latched = (uint16_t)(s->ccr >> 16);
        t->rawlatch = prev_rawcounts + hm2_wrap16((int32_t)latched - t->prev_reg_count);
        t->probe_pending = false;
        *probe_event = true;
    }
    int32_t diff = hm2_wrap16((int32_t)reg_count - t->prev_reg_count);
    t->rawcounts = (int32_t)((uint32_t)t->rawcounts + (uint32_t)diff);
    t->prev_reg_count = reg_count;

    if (t->state == HM2_ENCODER_STOPPED) {
        if (diff == 0)
            return index_event; /* still stopped */
        t->prev_event_rawcounts = t->rawcounts;
        t->prev_event_reg_timestamp = reg_ts;
        t->prev_time_of_interest = reg_ts;
        t->tsc_num_rollovers = 0;
        t->prev_dS_counts = 0;
        t->state = HM2_ENCODER_MOVING;
        return index_event;
    }

    uint16_t toi;
    if (diff != 0) {
        toi = reg_ts;
        if (toi < t->prev_time_of_interest)
            t->tsc_num_rollovers++;
        int32_t dS = t->rawcounts - t->prev_event_rawcounts;
        int64_t dT = ((int64_t)toi - t->prev_event_reg_timestamp) +
                     ((int64_t)t->tsc_num_rollovers << 16);
        if ((dS == 1 || dS == -1) && t->prev_dS_counts != 0 &&
            ((dS > 0) != (t->prev_dS_counts > 0))) {
            t->velocity = 0.0; /* one count back and forth: direction change */
        } else if (dT > 0) {
            t->velocity = ((double)dS / scale) / ((double)dT * seconds_per_tsc);
        }
        t->prev_dS_counts = dS;
        t->prev_event_rawcounts = t->rawcounts;
        t->prev_event_reg_timestamp = toi;
        t->tsc_num_rollovers = 0;
    } else {
        toi = s->tscount;
        if (toi < t->prev_time_of_interest)
            t->tsc_num_rollovers++;
        int64_t dT = ((int64_t)toi - t->prev_event_reg_timestamp) +
                     ((int64_t)t->tsc_num_rollovers << 16);
        double dT_s = (double)dT * seconds_per_tsc;
        if (dT_s >= vel_timeout) {
            t->velocity = 0.0;
            t->state = HM2_ENCODER_STOPPED;
            return index_event;
        }
        if (dT_s > 0.0) {
            /* no count yet: the speed is at most one count per dT */
            double bound = fabs(1.0 / scale) / dT_s;
            if (bound < fabs(t->velocity))
                t->velocity = t->velocity > 0 ? bound : -bound;
        }
    }
    t->prev_time_of_interest = toi;
    return index_event;
}

/* ---------------- PWMGen ---------------- */

struct hm2_pwm_rate hm2_pwmgen_pwm_rate(uint32_t pwm_frequency, uint32_t clock_high)
{
    struct hm2_pwm_rate r = {0};
    for (int bits = 12; bits >= 9; bits--) {
        double dds = floor((double)pwm_frequency * 65536.0 * (double)(1u << bits) /
                           (double)clock_high);
        if (dds < 65536.0) {
            r.bits = bits;
            r.dds = (uint32_t)dds;
            r.frequency = pwm_frequency;
            return r;
        }
    }
    r.bits = 9;
    r.dds = 65535;
    r.frequency = (uint32_t)((double)clock_high * 65535.0 / (65536.0 * 512.0));
    r.clipped = true;
    return r;
}

uint32_t hm2_pwmgen_pdm_rate(uint32_t pdm_frequency, uint32_t clock_high, int *clip)
{
    double dds = floor((double)pdm_frequency * 65536.0 / (double)clock_high);
    *clip = 0;
    if (dds < 1.0) {
        *clip = -1;
        return 1;
    }
    if (dds > 65535.0) {
        *clip = 1;
        return 65535;
    }
    return (uint32_t)dds;
}

uint32_t hm2_pwmgen_mode_word(int output_type, int pwm_bits, bool dither, bool *bad_type)
{
    uint32_t out_mode;
    *bad_type = false;
    switch (output_type) {
    case 1: out_mode = 0; break; /* PWM/Dir */
    case 2: out_mode = 2; break; /* Up/Down */
    case 3: out_mode = 3; break; /* PDM/Dir */
    case 4: out_mode = 1; break; /* Dir/PWM */
    default:
        *bad_type = true;
        out_mode = 0;
        output_type = 1;
        break;
    }
    uint32_t w = (uint32_t)(pwm_bits - 9) & 0x3;
    w |= out_mode << 3;
    if (output_type != 3)
        w |= 1u << 5; /* double buffer, not with PDM */
    if (dither)
        w |= 1u << 6;
    return w;
}

uint32_t hm2_pwmgen_value_register(double value, double scale, bool enable, int output_type,
                                   int pwm_bits, bool offset_mode, bool dither)
{
    double s = (scale != 0.0) ? value / scale : 0.0;
    if (!(s == s))
        s = 0.0; /* NaN */
    if (s > 1.0)
        s = 1.0;
    else if (s < -1.0)
        s = -1.0;
    if (!enable)
        s = 0.0;
    double t = dither ? 1.0625 : 1.0;
    bool pdm = output_type == 3;
    double v;
    if (offset_mode) {
        int bits = pdm ? 11 : pwm_bits - 1;
        double full = (double)(1u << bits);
        v = s * (full - t) + full;
    } else {
        int bits = pdm ? 12 : pwm_bits;
        v = fabs(s) * ((double)(1u << bits) - t);
    }
    uint32_t reg = (uint32_t)(v * 65536.0);
    if (s < 0.0)
        reg |= 0x80000000u;
    return reg;
}

/* ---------------- Watchdog ---------------- */

uint32_t hm2_watchdog_timer_value(uint32_t timeout_ns, uint32_t clock_low, bool *clipped)
{
    double v = (double)timeout_ns * ((double)clock_low / 1e9) - 1.0;
    *clipped = false;
    if (v < 0.0)
        v = 0.0;
    if (v >= 2147483648.0) {
        *clipped = true;
        return 0x7FFFFFFFu;
    }
    return (uint32_t)v;
}

uint32_t hm2_watchdog_max_timeout_ns(uint32_t clock_low)
{
    double ns = (double)0x7FFFFFFFu * 1e9 / (double)clock_low;
    return ns > 4294967295.0 ? 0xFFFFFFFFu : (uint32_t)ns;
}
