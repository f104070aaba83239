/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * scale - out = in * gain + offset.  As LinuxCNC 2.9's scale: float pins
 * in, gain, offset (IN, all default 0), out (OUT); function scale.N
 * (floating point).  See docs/scale.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_float_t *in;
    hal_float_t *gain;
    hal_float_t *offset;
    hal_float_t *out;
} scale_t;

static void scale_update(void *arg, long period)
{
    scale_t *p = arg;
    (void)period;
    *p->out = *p->in * *p->gain + *p->offset;
}

static const hm_item_t scale_pins[] = {
    HM_PIN(scale_t, in, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(scale_t, gain, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(scale_t, offset, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(scale_t, out, HAL_FLOAT, HAL_OUT, 0),
};

static const hm_comp_desc_t scale_desc = {
    .modname = "scale",
    .prefix = "scale",
    .inst_size = sizeof(scale_t),
    .pins = scale_pins,
    .npins = HM_COUNT(scale_pins),
    .funct = scale_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(scale_desc, "Applies a scale and offset to its input");
