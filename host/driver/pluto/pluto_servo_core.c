/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_servo_core.c - pluto_servo's read and write (spec/pluto.md §4).
 *
 * EPP traffic per servo period (spec §11):
 *   write: A(00) + 10 data writes (PWM0|PWM1<<16, PWM2|PWM3<<16, control)
 *   read:  A(00) + 4 data reads, status read, + 16 data reads
 * On a batching port (the virtual board) each function is one flush; the
 * read then queues all 20 reads before it knows the status (see
 * docs/pluto_servo.md, "Communication errors").
 */
#include <math.h>
#include <string.h>

#include "pluto_drivers.h"

void pluto_servo_defaults(struct pluto_servo *s)
{
    for (int i = 0; i < 4; i++) {
        s->enc_scale[i] = 1.0;
        s->pwm_offset[i] = 0.0;
        s->pwm_scale[i] = 1.0;
        s->pwm_max_dc[i] = 1.0;
        s->pwm_min_dc[i] = 0.0;
        s->pwm_pwmdir[i] = 0;
    }
    s->z_polarity = 0;
    s->is_pdm = 0;
    for (int i = 0; i < 20; i++)
        s->dout_invert[i] = 0;
    s->communication_error = 0;
    s->debug_0 = s->debug_1 = 0;
}

static int dbit(const struct pluto_servo *s, int k)
{
    return (*s->dout[k] ? 1 : 0) ^ (s->dout_invert[k] ? 1 : 0);
}

uint16_t pluto_servo_pwm_word(struct pluto_servo *s, int ch)
{
    double maxdc = s->pwm_max_dc[ch], mindc = s->pwm_min_dc[ch];
    /* the parameters are rewritten, as LinuxCNC does */
    if (!(maxdc <= 1.0))
        maxdc = 1.0;
    if (maxdc < 0.0)
        maxdc = 0.0;
    if (mindc > maxdc)
        mindc = maxdc;
    if (!(mindc >= 0.0))
        mindc = 0.0;
    s->pwm_max_dc[ch] = maxdc;
    s->pwm_min_dc[ch] = mindc;

    if (!*s->pwm_enable[ch])
        return 0;
    double v = *s->pwm_value[ch] / s->pwm_scale[ch] + s->pwm_offset[ch];
    if (isnan(v))
        v = 0.0;
    if (v > maxdc)
        v = maxdc;
    else if (v < -maxdc)
        v = -maxdc;
    if (v > 0 && v < mindc)
        v = mindc;
    else if (v < 0 && v > -mindc)
        v = -mindc;
    v *= 2047.0;
    if (v > 2047.0)
        v = 2047.0;
    if (v < -2047.0)
        v = -2047.0;
    uint16_t word = (uint16_t)(int)fabs(v);
    if (v < 0)
        word |= s->pwm_pwmdir[ch] ? (1u << 13) : (1u << 15);
    if (s->is_pdm)
        word |= 1u << 14;
    if (dbit(s, 10 + 2 * ch))
        word ^= 1u << 12;
    if (dbit(s, 11 + 2 * ch))
        word ^= 1u << 13;
    return word;
}

uint16_t pluto_servo_control_word(const struct pluto_servo *s)
{
    uint16_t w = 0;
    for (int i = 0; i < 10; i++)
        if (dbit(s, i))
            w |= (uint16_t)(1u << i);
    if (s->z_polarity)
        w |= 1u << 15;
    if (s->watchdog)
        w |= 1u << 14;
    if (s->test_encoder)
        w |= 1u << 13;
    return w;
}

void pluto_servo_write(struct pluto_servo *s, long period)
{
    (void)period;
    uint8_t w[10];
    if (s->communication_error)
        return;
    for (int ch = 0; ch < 4; ch++)
        pluto_put16(w + 2 * ch, pluto_servo_pwm_word(s, ch));
    pluto_put16(w + 8, pluto_servo_control_word(s));
    static const uint8_t sizes[3] = {4, 4, 2};
    pluto_write_transfer(s->port, w, sizes, 3, &s->communication_error, &s->log, "pluto-servo");
}

static void decode_encoder(struct pluto_servo *s, int i, uint32_t word, double fperiod)
{
    uint32_t newlow = word & 0x3FFFu;
    uint32_t indlow = (word >> 14) & 0x3FFFu;
    int indexed = (word >> 28) & 1;
    int64_t count = pluto_extend(s->last_count[i], newlow, 14);
    int64_t index = indexed ? pluto_extend(count, indlow, 14) : s->last_index[i];
    if (*s->enc_index_enable[i] && indexed) {
        *s->enc_index_enable[i] = 0;
        s->reset_count[i] = index;
    }
    int reset = *s->enc_reset[i] ? 1 : 0;
    if (reset)
        s->reset_count[i] = count;
    *s->enc_velocity[i] =
        reset ? 0.0 : (double)(count - s->last_count[i]) / s->enc_scale[i] / fperiod;
    s->last_count[i] = count;
    s->last_index[i] = index;
    *s->enc_count[i] = (int32_t)(count - s->reset_count[i]);
    *s->enc_position[i] = *s->enc_count[i] / s->enc_scale[i];
    if (i == 0) {
        s->debug_0 = (int32_t)word;
        s->debug_1 = (int32_t)count;
    }
}

void pluto_servo_read(struct pluto_servo *s, long period)
{
    double fperiod = period * 1e-9;
    if (!pluto_read_transfer(s->port, s->rbuf, &s->status, &s->communication_error, &s->log,
                             "pluto-servo"))
        return;
    for (int i = 0; i < 4; i++)
        decode_encoder(s, i, pluto_le32(s->rbuf + 4 * i), fperiod);
    uint32_t in = pluto_le32(s->rbuf + 16);
    for (int i = 0; i < 20; i++) {
        int b = (in >> i) & 1;
        *s->din[i] = b;
        *s->din_not[i] = !b;
    }
}
