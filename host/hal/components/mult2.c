/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * mult2 - product of two inputs: out = in0 * in1.  As LinuxCNC 2.9's
 * mult2: float pins in0, in1 (IN), out (OUT); function mult2.N (floating
 * point).  See docs/mult2.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_float_t *in0;
    hal_float_t *in1;
    hal_float_t *out;
} mult2_t;

static void mult2_update(void *arg, long period)
{
    mult2_t *p = arg;
    (void)period;
    *p->out = *p->in0 * *p->in1;
}

static const hm_item_t mult2_pins[] = {
    HM_PIN(mult2_t, in0, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(mult2_t, in1, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(mult2_t, out, HAL_FLOAT, HAL_OUT, 0),
};

static const hm_comp_desc_t mult2_desc = {
    .modname = "mult2",
    .prefix = "mult2",
    .inst_size = sizeof(mult2_t),
    .pins = mult2_pins,
    .npins = HM_COUNT(mult2_pins),
    .funct = mult2_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(mult2_desc, "Product of two inputs");
