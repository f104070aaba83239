/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtexample2.c - a realtime module written directly in C, the kind the
 * seed compiles with `comp --install rtexample2.c`: one s32 pin
 * rtexample2.out holding the module parameter value= (default 42).
 */
#include "rtapi.h"
#include "rtapi_app.h"
#include "rtapi_errno.h"
#include "hal.h"

MODULE_LICENSE("GPL");
static int comp_id;
static int value = 42;
RTAPI_MP_INT(value, "initial value");
static hal_s32_t **out; /* the pin pointer lives in HAL memory */

int rtapi_app_main(void)
{
    comp_id = hal_init("rtexample2");
    if (comp_id < 0)
        return comp_id;
    out = hal_malloc(sizeof(*out));
    int r = out ? hal_pin_s32_new("rtexample2.out", HAL_OUT, out, comp_id) : -ENOMEM;
    if (r < 0) {
        hal_exit(comp_id);
        return r;
    }
    **out = value;
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void) { hal_exit(comp_id); }
