/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * mux2 - select one of two inputs: out = sel ? in1 : in0.  As LinuxCNC
 * 2.9's mux2: bit sel, float in0, in1 (IN), float out (OUT); function
 * mux2.N (floating point).  See docs/mux2.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_bit_t *sel;
    hal_float_t *out;
    hal_float_t *in0;
    hal_float_t *in1;
} mux2_t;

static void mux2_update(void *arg, long period)
{
    mux2_t *p = arg;
    (void)period;
    *p->out = *p->sel ? *p->in1 : *p->in0;
}

static const hm_item_t mux2_pins[] = {
    HM_PIN(mux2_t, sel, HAL_BIT, HAL_IN, 0),
    HM_PIN(mux2_t, out, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(mux2_t, in0, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(mux2_t, in1, HAL_FLOAT, HAL_IN, 0),
};

static const hm_comp_desc_t mux2_desc = {
    .modname = "mux2",
    .prefix = "mux2",
    .inst_size = sizeof(mux2_t),
    .pins = mux2_pins,
    .npins = HM_COUNT(mux2_pins),
    .funct = mux2_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(mux2_desc, "Select from one of two input values");
