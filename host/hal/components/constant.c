/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * constant - drive a float pin from a parameter: out = value.  As LinuxCNC
 * 2.9's constant: float pin out (OUT), float parameter value (RW, 0);
 * function constant.N (floating point).  See docs/constant.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_float_t *out;
    hal_float_t value;
} constant_t;

static void constant_update(void *arg, long period)
{
    constant_t *p = arg;
    (void)period;
    *p->out = p->value;
}

static const hm_item_t constant_pins[] = {
    HM_PIN(constant_t, out, HAL_FLOAT, HAL_OUT, 0),
};

static const hm_item_t constant_params[] = {
    HM_PIN(constant_t, value, HAL_FLOAT, HAL_RW, 0),
};

static const hm_comp_desc_t constant_desc = {
    .modname = "constant",
    .prefix = "constant",
    .inst_size = sizeof(constant_t),
    .pins = constant_pins,
    .npins = HM_COUNT(constant_pins),
    .params = constant_params,
    .nparams = HM_COUNT(constant_params),
    .funct = constant_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(constant_desc, "Use a parameter to set the value of a pin");
