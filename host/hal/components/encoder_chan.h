/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * encoder_chan.h - one channel of the encoder component (encoder.comp):
 * its HAL pins and its counter (math/encoder_math.h).  A header because
 * the .comp's instance structure holds an array of these.
 */
#ifndef HM_ENCODER_CHAN_H
#define HM_ENCODER_CHAN_H

#include "hal.h"
#include "math/encoder_math.h"

typedef struct {
    hal_bit_t *phase_a, *phase_b, *phase_z;
    hal_bit_t *index_enable, *reset, *counter_mode, *x4_mode;
    hal_bit_t *latch_in, *latch_rising, *latch_falling;
    hal_s32_t *counts, *counts_latched, *rawcounts, *missing_teeth;
    hal_float_t *position, *position_latched, *position_interp;
    hal_float_t *velocity, *velocity_rpm, *position_scale, *min_speed;
    enc_t e;
} enc_chan_t;

#endif /* HM_ENCODER_CHAN_H */
