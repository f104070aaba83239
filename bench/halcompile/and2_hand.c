/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * and2_hand - bench-only: and2 written by hand against hal.h, the way a C
 * component is written without halcompile (no libhalcomp, no tables), to
 * compare its per-call cost with the halcompile-built and2.  Pins
 * and2-hand.N.in0/in1/out, function and2-hand.N; count= only.
 */
#include <errno.h>

#include "hal.h"
#include "rtapi.h"

typedef struct {
    hal_bit_t *in0;
    hal_bit_t *in1;
    hal_bit_t *out;
} and2_hand_t;

static int count = 1;
RTAPI_MP_INT(count, "number of instances");
static int comp_id;
MODULE_LICENSE("GPL");

static void and2_hand(void *arg, long period)
{
    and2_hand_t *p = arg;
    (void)period;
    *p->out = *p->in0 && *p->in1;
}

static int make_one(int i)
{
    and2_hand_t *p = hal_malloc(sizeof(*p));
    if (p == NULL)
        return -ENOMEM;
    int r = hal_pin_bit_newf(HAL_IN, &p->in0, comp_id, "and2-hand.%d.in0", i);
    if (r == 0)
        r = hal_pin_bit_newf(HAL_IN, &p->in1, comp_id, "and2-hand.%d.in1", i);
    if (r == 0)
        r = hal_pin_bit_newf(HAL_OUT, &p->out, comp_id, "and2-hand.%d.out", i);
    if (r == 0)
        r = hal_export_functf(and2_hand, p, 0, 0, comp_id, "and2-hand.%d", i);
    return r;
}

int rtapi_app_main(void)
{
    comp_id = hal_init("and2_hand");
    if (comp_id < 0)
        return comp_id;
    for (int i = 0; i < count; i++) {
        int r = make_one(i);
        if (r != 0) {
            hal_exit(comp_id);
            return r;
        }
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
}
