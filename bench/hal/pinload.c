/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pinload - a realtime module for bench/hal only (built by run.sh, loaded
 * from a temporary HAL_RTLIB_PATH): `loadrt pinload count=N` makes N
 * and2-like instances pinload.I with pins in0, in1, out and one function
 * each, so a thread can touch 1k, 10k or 100k HAL pins (the components
 * built by halcompile stop at count=1000).
 */
#include <errno.h>

#include "hal.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");

static int count = 1;
RTAPI_MP_INT(count, "number of instances (1..100000)");

typedef struct {
    hal_bit_t *in0, *in1, *out;
} inst_t;

static int comp_id = -1;

static void and_fn(void *arg, long period)
{
    inst_t *p = arg;
    (void)period;
    *p->out = *p->in0 && *p->in1;
}

int rtapi_app_main(void)
{
    if (count < 1 || count > 100000) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pinload: count=%d out of range (1..100000)\n", count);
        return -EINVAL;
    }
    comp_id = hal_init("pinload");
    if (comp_id < 0)
        return comp_id;
    inst_t *v = hal_malloc((long)count * (long)sizeof(*v));
    int r = v ? 0 : -ENOMEM;
    for (int i = 0; i < count && r == 0; i++) {
        if ((r = hal_pin_bit_newf(HAL_IN, &v[i].in0, comp_id, "pinload.%d.in0", i)) ||
            (r = hal_pin_bit_newf(HAL_IN, &v[i].in1, comp_id, "pinload.%d.in1", i)) ||
            (r = hal_pin_bit_newf(HAL_OUT, &v[i].out, comp_id, "pinload.%d.out", i)))
            break;
        r = hal_export_functf(and_fn, &v[i], 0, 0, comp_id, "pinload.%d", i);
    }
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pinload: instance setup failed (%d)\n", r);
        hal_exit(comp_id);
        return r;
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
}
