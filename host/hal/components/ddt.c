/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * ddt - derivative of the input: out = (in - previous in) / period.  As
 * LinuxCNC 2.9's ddt: float in (IN), out (OUT); function ddt.N (floating
 * point).  The first call differentiates against 0.  See docs/ddt.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_float_t *in;
    hal_float_t *out;
    double old;
} ddt_t;

static void ddt_update(void *arg, long period)
{
    ddt_t *p = arg;
    double in = *p->in;
    *p->out = (in - p->old) / (period * 1e-9);
    p->old = in;
}

static const hm_item_t ddt_pins[] = {
    HM_PIN(ddt_t, in, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(ddt_t, out, HAL_FLOAT, HAL_OUT, 0),
};

static const hm_comp_desc_t ddt_desc = {
    .modname = "ddt",
    .prefix = "ddt",
    .inst_size = sizeof(ddt_t),
    .pins = ddt_pins,
    .npins = HM_COUNT(ddt_pins),
    .funct = ddt_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(ddt_desc, "Computes the derivative of the input function");
