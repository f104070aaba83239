/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * abs - absolute value and sign of a float.  Pins as LinuxCNC 2.9's abs:
 * float in (IN); float out, bit sign, is-positive, is-negative (OUT);
 * function abs.N (floating point).
 *
 * The corner cases follow what 2.9 produces (checked with its halsampler):
 * -0.0 gives out 0.0 and sign FALSE; NaN takes the "negative" branch (sign
 * TRUE, out = -NaN) while is-positive and is-negative are both FALSE;
 * is-positive/is-negative need |in| > 1e-6.
 * See docs/abs.md.
 */
#include <math.h>

#include "hm_simple.h"

#define ABS_DEADBAND 0.000001

typedef struct {
    hal_float_t *in;
    hal_float_t *out;
    hal_bit_t *sign;
    hal_bit_t *is_positive;
    hal_bit_t *is_negative;
} abs_t;

static void abs_update(void *arg, long period)
{
    abs_t *p = arg;
    double in = *p->in;
    (void)period;
    if (in >= 0.0) {
        *p->sign = 0;
        *p->out = fabs(in);
    } else {
        *p->sign = 1;
        *p->out = -in;
    }
    /* 2.9 reports a sign only beyond +-1e-6 (checked on it: 1e-6 -> FALSE,
     * 1.1e-6 -> TRUE), a deadband its man page does not mention */
    *p->is_positive = in > ABS_DEADBAND;
    *p->is_negative = in < -ABS_DEADBAND;
}

static const hm_item_t abs_pins[] = {
    HM_PIN(abs_t, in, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(abs_t, out, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(abs_t, sign, HAL_BIT, HAL_OUT, 0),
    HM_PIN_N(abs_t, is_positive, "is-positive", HAL_BIT, HAL_OUT, 0),
    HM_PIN_N(abs_t, is_negative, "is-negative", HAL_BIT, HAL_OUT, 0),
};

static const hm_comp_desc_t abs_desc = {
    .modname = "abs",
    .prefix = "abs",
    .inst_size = sizeof(abs_t),
    .pins = abs_pins,
    .npins = HM_COUNT(abs_pins),
    .funct = abs_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(abs_desc, "Compute the absolute value and sign of the input signal");
