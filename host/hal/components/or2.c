/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * or2 - Two-input OR gate.  Pins and names as LinuxCNC 2.9's or2:
 * bit in0, in1 (IN), bit out (OUT); function or2.N (no floating point).
 * See docs/or2.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_bit_t *in0;
    hal_bit_t *in1;
    hal_bit_t *out;
} or2_t;

static void or2_update(void *arg, long period)
{
    or2_t *p = arg;
    (void)period;
    *p->out = (*p->in0) || (*p->in1);
}

static const hm_item_t or2_pins[] = {
    HM_PIN(or2_t, in0, HAL_BIT, HAL_IN, 0),
    HM_PIN(or2_t, in1, HAL_BIT, HAL_IN, 0),
    HM_PIN(or2_t, out, HAL_BIT, HAL_OUT, 0),
};

static const hm_comp_desc_t or2_desc = {
    .modname = "or2",
    .prefix = "or2",
    .inst_size = sizeof(or2_t),
    .pins = or2_pins,
    .npins = HM_COUNT(or2_pins),
    .funct = or2_update,
    .uses_fp = 0,
};

HM_SIMPLE_COMPONENT(or2_desc, "Two-input OR gate");
