/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pwmgen_chan.h - one channel of the pwmgen component (pwmgen.comp): its
 * HAL pins and its pulse maker (math/pwmgen_math.h).  A header because the
 * .comp's instance structure holds arrays of these.
 */
#ifndef HM_PWMGEN_CHAN_H
#define HM_PWMGEN_CHAN_H

#include "hal.h"
#include "math/pwmgen_math.h"

/* What make-pulses touches, kept together for all channels. */
typedef struct {
    pwm_pulse_t q;
    uint8_t type;             /* output_type: 0 pwm, 1 pwm+dir, 2 up/down */
    hal_bit_t *out_a, *out_b; /* pwm and dir, or up and down */
} pwmgen_hot_t;

typedef struct {
    hal_float_t *value, *scale, *offset, *freq, *min_dc, *max_dc, *curr_dc;
    hal_bit_t *enable, *dither;
    pwm_t p;
} pwmgen_chan_t;

#endif /* HM_PWMGEN_CHAN_H */
