/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * xor2 - Two-input XOR (exclusive OR) gate.  Pins and names as LinuxCNC 2.9's xor2:
 * bit in0, in1 (IN), bit out (OUT); function xor2.N (no floating point).
 * See docs/xor2.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_bit_t *in0;
    hal_bit_t *in1;
    hal_bit_t *out;
} xor2_t;

static void xor2_update(void *arg, long period)
{
    xor2_t *p = arg;
    (void)period;
    *p->out = (*p->in0) != (*p->in1);
}

static const hm_item_t xor2_pins[] = {
    HM_PIN(xor2_t, in0, HAL_BIT, HAL_IN, 0),
    HM_PIN(xor2_t, in1, HAL_BIT, HAL_IN, 0),
    HM_PIN(xor2_t, out, HAL_BIT, HAL_OUT, 0),
};

static const hm_comp_desc_t xor2_desc = {
    .modname = "xor2",
    .prefix = "xor2",
    .inst_size = sizeof(xor2_t),
    .pins = xor2_pins,
    .npins = HM_COUNT(xor2_pins),
    .funct = xor2_update,
    .uses_fp = 0,
};

HM_SIMPLE_COMPONENT(xor2_desc, "Two-input XOR (exclusive OR) gate");
