/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * lowpass - first-order low-pass filter: out += (in - out) * gain, or
 * out = in while load is TRUE.  As LinuxCNC 2.9's lowpass: float in (IN),
 * bit load (IN), float out (OUT), float parameter gain (RW, default 0);
 * function lowpass.N (floating point).  See docs/lowpass.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_float_t *in;
    hal_float_t *out;
    hal_bit_t *load;
    hal_float_t gain;
} lowpass_t;

static void lowpass_update(void *arg, long period)
{
    lowpass_t *p = arg;
    (void)period;
    if (*p->load)
        *p->out = *p->in;
    else
        *p->out += (*p->in - *p->out) * p->gain;
}

static const hm_item_t lowpass_pins[] = {
    HM_PIN(lowpass_t, in, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(lowpass_t, out, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(lowpass_t, load, HAL_BIT, HAL_IN, 0),
};

static const hm_item_t lowpass_params[] = {
    HM_PIN(lowpass_t, gain, HAL_FLOAT, HAL_RW, 0),
};

static const hm_comp_desc_t lowpass_desc = {
    .modname = "lowpass",
    .prefix = "lowpass",
    .inst_size = sizeof(lowpass_t),
    .pins = lowpass_pins,
    .npins = HM_COUNT(lowpass_pins),
    .params = lowpass_params,
    .nparams = HM_COUNT(lowpass_params),
    .funct = lowpass_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(lowpass_desc, "Low-pass filter");
