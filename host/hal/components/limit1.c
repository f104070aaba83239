/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * limit1 - limit the output to min..max.  As LinuxCNC 2.9's limit1: float
 * in, min (default -1e20), max (default 1e20) (IN), out (OUT); function
 * limit1.N (floating point).  See docs/limit1.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_float_t *in;
    hal_float_t *out;
    hal_float_t *min;
    hal_float_t *max;
} limit1_t;

static void limit1_update(void *arg, long period)
{
    limit1_t *p = arg;
    double v = *p->in;
    (void)period;
    if (v < *p->min)
        v = *p->min;
    if (v > *p->max)
        v = *p->max;
    *p->out = v;
}

static const hm_item_t limit1_pins[] = {
    HM_PIN(limit1_t, in, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(limit1_t, out, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(limit1_t, min, HAL_FLOAT, HAL_IN, -1e20),
    HM_PIN(limit1_t, max, HAL_FLOAT, HAL_IN, 1e20),
};

static const hm_comp_desc_t limit1_desc = {
    .modname = "limit1",
    .prefix = "limit1",
    .inst_size = sizeof(limit1_t),
    .pins = limit1_pins,
    .npins = HM_COUNT(limit1_pins),
    .funct = limit1_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(limit1_desc, "Limit the output signal to fall between min and max");
