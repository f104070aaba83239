/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * abs_s32 - absolute value and sign of an s32.  Pins as LinuxCNC 2.9's
 * abs_s32 (prefix abs-s32): s32 in (IN); s32 out, bit sign, is-positive,
 * is-negative (OUT); function abs-s32.N (no floating point).
 * -2147483648 has no positive s32 counterpart: out wraps to -2147483648
 * as in 2.9, computed without signed overflow.  See docs/abs_s32.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_s32_t *in;
    hal_s32_t *out;
    hal_bit_t *sign;
    hal_bit_t *is_positive;
    hal_bit_t *is_negative;
} abs_s32_t;

static void abs_s32_update(void *arg, long period)
{
    abs_s32_t *p = arg;
    rtapi_s32 in = *p->in;
    (void)period;
    if (in >= 0) {
        *p->sign = 0;
        *p->out = in;
    } else {
        *p->sign = 1;
        *p->out = (rtapi_s32)(0u - (rtapi_u32)in);
    }
    *p->is_positive = in > 0;
    *p->is_negative = in < 0;
}

static const hm_item_t abs_s32_pins[] = {
    HM_PIN(abs_s32_t, in, HAL_S32, HAL_IN, 0),
    HM_PIN(abs_s32_t, out, HAL_S32, HAL_OUT, 0),
    HM_PIN(abs_s32_t, sign, HAL_BIT, HAL_OUT, 0),
    HM_PIN_N(abs_s32_t, is_positive, "is-positive", HAL_BIT, HAL_OUT, 0),
    HM_PIN_N(abs_s32_t, is_negative, "is-negative", HAL_BIT, HAL_OUT, 0),
};

static const hm_comp_desc_t abs_s32_desc = {
    .modname = "abs_s32",
    .prefix = "abs-s32",
    .inst_size = sizeof(abs_s32_t),
    .pins = abs_s32_pins,
    .npins = HM_COUNT(abs_s32_pins),
    .funct = abs_s32_update,
    .uses_fp = 0,
};

HM_SIMPLE_COMPONENT(abs_s32_desc, "Compute the absolute value and sign of an s32 input");
