/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_step_core.c - pluto_step's read and write (spec/pluto.md §6).
 *
 * EPP traffic per servo period (spec §11):
 *   write: A(00) + 12 data writes (4 velocities, outputs, timing)
 *   read:  A(00) + 4 data reads, status read, + 16 data reads
 * The computations are LinuxCNC 2.9's as coded, including the oddities
 * listed in spec §12 (see docs/pluto_step.md).  One deliberate difference:
 * with the `watchdog` modparam (default 1) bit 14 of the output word is
 * set, which arms the firmware watchdog as the Pluto-P documentation says
 * ("enabled (the default)"); watchdog=0 gives LinuxCNC 2.9's exact words.
 */
#include <math.h>
#include <string.h>

#include "pluto_drivers.h"

#define STEP_TICK_NS 1600u
#define STEP_MAX_TICKS 31
#define STEP_FRAC_BITS 11

void pluto_step_defaults(struct pluto_step *s)
{
    for (int i = 0; i < 4; i++) {
        s->scale[i] = 1.0;
        s->maxvel[i] = 0.0;
    }
    s->step_polarity = 0;
    s->steplen = s->stepspace = s->dirtime = 0;
    for (int i = 0; i < 14; i++)
        s->dout_invert[i] = 0;
    s->communication_error = 0;
    s->debug_0 = s->debug_1 = 0;
    s->debug_2 = 0.5;
    s->debug_3 = 2.0;
}

int pluto_step_ticks(uint32_t ns)
{
    uint32_t t = ns / STEP_TICK_NS;
    return t > STEP_MAX_TICKS ? STEP_MAX_TICKS : (int)t;
}

uint16_t pluto_step_timing_word(const struct pluto_step *s)
{
    uint16_t w = (uint16_t)(pluto_step_ticks(s->steplen) | pluto_step_ticks(s->dirtime) << 8);
    if (s->step_polarity)
        w |= 0x8000u;
    return w;
}

uint16_t pluto_step_dout_word(const struct pluto_step *s)
{
    uint16_t w = 0;
    for (int i = 0; i < 14; i++)
        if ((*s->dout[i] ? 1 : 0) ^ (s->dout_invert[i] ? 1 : 0))
            w |= (uint16_t)(1u << i);
    if (s->watchdog)
        w |= 1u << 14;
    return w;
}

static void clamp_time(struct pluto_step *s, hal_u32_t *param, const char *what)
{
    if (*param / STEP_TICK_NS > STEP_MAX_TICKS) {
        if (s->log.fn)
            s->log.fn(s->log.ctx, PLUTO_ERR,
                      "Requested %s %dns decreased to %dns due to hardware limitations\n", what,
                      (int)*param, STEP_MAX_TICKS * STEP_TICK_NS);
        *param = STEP_MAX_TICKS * STEP_TICK_NS;
    }
}

static int step_rate(struct pluto_step *s, int i, double fmax, double fperiod)
{
    double new_cmd = *s->position_cmd[i];
    double v = new_cmd - s->old_position_cmd[i];
    double est_err = *s->position_fb[i] + s->old_velocity_cmd[i] * fperiod - new_cmd;
    double scale_abs = fabs(s->scale[i]);
    v = v - s->debug_2 * est_err / fperiod;
    if (v > 0)
        v = v + 0.5 / scale_abs;
    else if (v < 0)
        v = v - 0.5 / scale_abs;
    s->old_position_cmd[i] = new_cmd;
    s->old_velocity_cmd[i] = v;

    double actual_max = fmax / scale_abs;
    if (s->maxvel[i] < 0)
        s->maxvel[i] = -s->maxvel[i];
    if (s->maxvel[i] != 0 && s->maxvel[i] > actual_max) {
        if (!s->maxvel_msg_printed[i] && s->log.fn) {
            s->log.fn(s->log.ctx, PLUTO_ERR,
                      "Requested step rate %dHz decreased to %dHz due to hardware or timing "
                      "limitations\n",
                      (int)(s->maxvel[i] * scale_abs), (int)fmax);
        }
        s->maxvel_msg_printed[i] = 1;
        s->maxvel[i] = actual_max;
    }
    double lim = s->maxvel[i] != 0 ? s->maxvel[i] : actual_max;
    if (v > lim)
        v = lim;
    if (v < -lim)
        v = -lim;
    if (!*s->enable[i])
        return 0;
    double rf = v * s->scale[i] * (1 << STEP_FRAC_BITS) * 1.6e-6 / (1 << s->speedrange);
    if (isnan(rf))
        return 0;
    if (rf > 1024)
        rf = 1024;
    if (rf < -1024)
        rf = -1024;
    return (int)rf;
}

void pluto_step_write(struct pluto_step *s, long period)
{
    double fperiod = period * 1e-9;
    clamp_time(s, &s->steplen, "step length");
    clamp_time(s, &s->dirtime, "direction change time");
    int steplen_t = pluto_step_ticks(s->steplen);
    int stepspace_t = (int)(s->stepspace / STEP_TICK_NS);
    double fmax = 625000.0 / (2 + steplen_t + stepspace_t);
    /* as coded in LinuxCNC (spec §12: assigns a time, only reachable with
     * speedrange > 0) */
    if (fmax > 625000.0 / (1 << (s->speedrange + 1)))
        fmax = 1.6e-6 * (1 << (s->speedrange + 1));
    double lim2 = ((1 << 20) - 1) / fperiod / (1 << s->speedrange);
    if (fmax > lim2)
        fmax = lim2;
    if (s->communication_error)
        return;

    uint8_t w[12];
    for (int i = 0; i < 4; i++) {
        int rate = step_rate(s, i, fmax, fperiod);
        if (i == 0)
            s->debug_1 = rate;
        pluto_put16(w + 2 * i, (uint16_t)(int16_t)rate);
    }
    pluto_put16(w + 8, pluto_step_dout_word(s));
    pluto_put16(w + 10, pluto_step_timing_word(s));
    static const uint8_t sizes[6] = {2, 2, 2, 2, 2, 2};
    pluto_write_transfer(s->port, w, sizes, 6, &s->communication_error, &s->log, "pluto-step");
}

void pluto_step_read(struct pluto_step *s, long period)
{
    double fperiod = period * 1e-9;
    if (!pluto_read_transfer(s->port, s->rbuf, &s->status, &s->communication_error, &s->log,
                             "pluto-step"))
        return;
    for (int i = 0; i < 4; i++) {
        uint32_t word = pluto_le32(s->rbuf + 4 * i);
        int64_t count = pluto_extend(s->last_count[i], word & 0x1FFFFFu, 21);
        *s->velocity_fb[i] =
            (double)(count - s->last_count[i]) / s->scale[i] / fperiod / (1 << STEP_FRAC_BITS);
        s->last_count[i] = count;
        if (*s->reset[i])
            s->reset_count[i] = count;
        double f = (double)(count - s->reset_count[i]) / (1 << STEP_FRAC_BITS);
        *s->counts[i] = (int32_t)f;
        *s->position_fb[i] = f / s->scale[i];
        if (i == 0)
            s->debug_0 = (int32_t)word;
    }
    uint32_t in = pluto_le32(s->rbuf + 16);
    for (int i = 0; i < 16; i++) {
        int b = (in >> i) & 1;
        *s->din[i] = b;
        *s->din_not[i] = !b;
    }
}
