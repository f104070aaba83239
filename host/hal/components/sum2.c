/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * sum2 - weighted sum of two inputs: out = in0 * gain0 + in1 * gain1 +
 * offset.  As LinuxCNC 2.9's sum2: float pins in0, in1 (IN), out (OUT);
 * float parameters gain0 = 1, gain1 = 1, offset = 0 (RW); function sum2.N
 * (floating point).  See docs/sum2.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_float_t *in0;
    hal_float_t *in1;
    hal_float_t *out;
    hal_float_t gain0;
    hal_float_t gain1;
    hal_float_t offset;
} sum2_t;

static void sum2_update(void *arg, long period)
{
    sum2_t *p = arg;
    (void)period;
    *p->out = *p->in0 * p->gain0 + *p->in1 * p->gain1 + p->offset;
}

static const hm_item_t sum2_pins[] = {
    HM_PIN(sum2_t, in0, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(sum2_t, in1, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(sum2_t, out, HAL_FLOAT, HAL_OUT, 0),
};

static const hm_item_t sum2_params[] = {
    HM_PIN(sum2_t, gain0, HAL_FLOAT, HAL_RW, 1.0),
    HM_PIN(sum2_t, gain1, HAL_FLOAT, HAL_RW, 1.0),
    HM_PIN(sum2_t, offset, HAL_FLOAT, HAL_RW, 0.0),
};

static const hm_comp_desc_t sum2_desc = {
    .modname = "sum2",
    .prefix = "sum2",
    .inst_size = sizeof(sum2_t),
    .pins = sum2_pins,
    .npins = HM_COUNT(sum2_pins),
    .params = sum2_params,
    .nparams = HM_COUNT(sum2_params),
    .funct = sum2_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(sum2_desc, "Sum of two inputs (each with a gain) and an offset");
