/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * not - inverter.  Pins and names as LinuxCNC 2.9's not: bit in (IN),
 * bit out (OUT); function not.N (no floating point).  See docs/not.md.
 */
#include "hm_simple.h"

typedef struct {
    hal_bit_t *in;
    hal_bit_t *out;
} not_t;

static void not_update(void *arg, long period)
{
    not_t *p = arg;
    (void)period;
    *p->out = !*p->in;
}

static const hm_item_t not_pins[] = {
    HM_PIN(not_t, in, HAL_BIT, HAL_IN, 0),
    HM_PIN(not_t, out, HAL_BIT, HAL_OUT, 0),
};

static const hm_comp_desc_t not_desc = {
    .modname = "not",
    .prefix = "not",
    .inst_size = sizeof(not_t),
    .pins = not_pins,
    .npins = HM_COUNT(not_pins),
    .funct = not_update,
    .uses_fp = 0,
};

HM_SIMPLE_COMPONENT(not_desc, "Inverter");
