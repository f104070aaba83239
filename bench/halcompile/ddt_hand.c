/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * ddt_hand - bench-only: ddt written by hand against hal.h (floating point,
 * per-instance state), to compare with the halcompile-built ddt.  Pins
 * ddt-hand.N.in/out, function ddt-hand.N; count= only.
 */
#include <errno.h>

#include "hal.h"
#include "rtapi.h"

typedef struct {
    hal_float_t *in;
    hal_float_t *out;
    double old;
} ddt_hand_t;

static int count = 1;
RTAPI_MP_INT(count, "number of instances");
static int comp_id;
MODULE_LICENSE("GPL");

static void ddt_hand(void *arg, long period)
{
    ddt_hand_t *p = arg;
    double v = *p->in;
    *p->out = (v - p->old) / (period * 1e-9);
    p->old = v;
}

static int make_one(int i)
{
    ddt_hand_t *p = hal_malloc(sizeof(*p));
    if (p == NULL)
        return -ENOMEM;
    p->old = 0;
    int r = hal_pin_float_newf(HAL_IN, &p->in, comp_id, "ddt-hand.%d.in", i);
    if (r == 0)
        r = hal_pin_float_newf(HAL_OUT, &p->out, comp_id, "ddt-hand.%d.out", i);
    if (r == 0)
        r = hal_export_functf(ddt_hand, p, 1, 0, comp_id, "ddt-hand.%d", i);
    return r;
}

int rtapi_app_main(void)
{
    comp_id = hal_init("ddt_hand");
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
