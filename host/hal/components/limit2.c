/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * limit2 - limit the output to min..max and its rate of change to maxv
 * per second.  As LinuxCNC 2.9's limit2: float in, min (-1e20), max
 * (1e20), maxv (1e20) and bit load (IN), float out (OUT); function
 * limit2.N (floating point).
 *
 * Each period the input is clamped to min..max (min first, so max wins
 * when they cross); with load TRUE that is the output at once, otherwise
 * the output moves towards it by at most maxv * period.  The rate limit is
 * applied last, so after min/max jump the output walks towards the new
 * range (checked against 2.9).  See docs/limit2.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_float_t *in;
    hal_float_t *out;
    hal_bit_t *load;
    hal_float_t *min;
    hal_float_t *max;
    hal_float_t *maxv;
    double old;
} limit2_t;

static void limit2_update(void *arg, long period)
{
    limit2_t *p = arg;
    double v = *p->in;
    if (v < *p->min)
        v = *p->min;
    if (v > *p->max)
        v = *p->max;
    if (!*p->load) {
        double step = *p->maxv * (period * 1e-9);
        if (v > p->old + step)
            v = p->old + step;
        if (v < p->old - step)
            v = p->old - step;
    }
    p->old = v;
    *p->out = v;
}

static const hm_item_t limit2_pins[] = {
    HM_PIN(limit2_t, in, HAL_FLOAT, HAL_IN, 0),
    HM_PIN(limit2_t, out, HAL_FLOAT, HAL_OUT, 0),
    HM_PIN(limit2_t, load, HAL_BIT, HAL_IN, 0),
    HM_PIN(limit2_t, min, HAL_FLOAT, HAL_IN, -1e20),
    HM_PIN(limit2_t, max, HAL_FLOAT, HAL_IN, 1e20),
    HM_PIN(limit2_t, maxv, HAL_FLOAT, HAL_IN, 1e20),
};

static const hm_comp_desc_t limit2_desc = {
    .modname = "limit2",
    .prefix = "limit2",
    .inst_size = sizeof(limit2_t),
    .pins = limit2_pins,
    .npins = HM_COUNT(limit2_pins),
    .funct = limit2_update,
    .uses_fp = 1,
};

HM_SIMPLE_COMPONENT(limit2_desc, "Limit the output signal to fall between min and max and "
                                 "limit its slew rate to less than maxv per second");
