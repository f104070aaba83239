/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * and2 - Two-input AND gate.  Pins and names as LinuxCNC 2.9's and2:
 * bit in0, in1 (IN), bit out (OUT); function and2.N (no floating point).
 * See docs/and2.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_bit_t *in0;
    hal_bit_t *in1;
    hal_bit_t *out;
} and2_t;

static void and2_update(void *arg, long period)
{
    and2_t *p = arg;
    (void)period;
    *p->out = (*p->in0) && (*p->in1);
}

static const hm_item_t and2_pins[] = {
    HM_PIN(and2_t, in0, HAL_BIT, HAL_IN, 0),
    HM_PIN(and2_t, in1, HAL_BIT, HAL_IN, 0),
    HM_PIN(and2_t, out, HAL_BIT, HAL_OUT, 0),
};

static const hm_comp_desc_t and2_desc = {
    .modname = "and2",
    .prefix = "and2",
    .inst_size = sizeof(and2_t),
    .pins = and2_pins,
    .npins = HM_COUNT(and2_pins),
    .funct = and2_update,
    .uses_fp = 0,
};

HM_SIMPLE_COMPONENT(and2_desc, "Two-input AND gate");
