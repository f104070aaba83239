/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm_testmod - realtime component for HAL core tests (not a product
 * component; lives in lib/rtlib-test).
 *
 *   loadrt hm_testmod [count=N] [fail=1] [label=TEXT] [values=a,b,c] [verbose=1]
 *
 * Instance i has pins hm-testmod.i.{bit,float,s32,u32,s64,u64}-{in,out,io},
 * parameters hm-testmod.i.{bit,float,s32,u32,s64,u64}-{ro,rw} and a function
 * hm-testmod.i.update that copies each -in pin to the matching -out pin,
 * counts its calls in `calls` (u32 OUT), stores rtapi_get_time() in `now`
 * (s64 OUT) and the period it was called with in `period` (s32 OUT).
 * While the `hold` pin is TRUE it first waits like sampler/streamer do,
 * `while (hold && !rtapi_sim_yield())`, counting in `yields`.
 * On the wall clock, when `spin-every` (u32 IN) is N > 0, every Nth call
 * (calls N-1, 2N-1, ...) busy-waits `spin-ns` (s32 IN) nanoseconds first,
 * counted in `spins` (u32 OUT): a function whose run time varies, for the
 * .time/.tmax tests.
 * fail=1 makes rtapi_app_main fail after creating pins (tests that a
 * failed loadrt leaves nothing behind).
 */
#include <errno.h>

#include "hal.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");

static int count = 1;
RTAPI_MP_INT(count, "number of instances");
static int fail = 0;
RTAPI_MP_INT(fail, "fail after creating the pins");
static char *label = "none";
RTAPI_MP_STRING(label, "a string parameter, echoed in rtapi messages");
static long values[4] = {0, 0, 0, 0};
RTAPI_MP_ARRAY_LONG(values, 4, "up to 4 longs, echoed in rtapi messages");
static int verbose = 0;
RTAPI_MP_INT(verbose, "1: print an INFO message when loaded");

typedef struct {
    hal_bit_t *bit_in, *bit_out, *bit_io;
    hal_float_t *float_in, *float_out, *float_io;
    hal_s32_t *s32_in, *s32_out, *s32_io;
    hal_u32_t *u32_in, *u32_out, *u32_io;
    hal_s64_t *s64_in, *s64_out, *s64_io;
    hal_u64_t *u64_in, *u64_out, *u64_io;
    hal_u32_t *calls;
    hal_bit_t *hold;   /* while TRUE, update waits with rtapi_sim_yield() */
    hal_u32_t *yields; /* rtapi_sim_yield() calls that said "keep waiting" */
    hal_s64_t *now;
    hal_s32_t *period;
    hal_u32_t *spin_every, *spins;
    hal_s32_t *spin_ns;
    hal_bit_t bit_ro, bit_rw;
    hal_float_t float_ro, float_rw;
    hal_s32_t s32_ro, s32_rw;
    hal_u32_t u32_ro, u32_rw;
    hal_s64_t s64_ro, s64_rw;
    hal_u64_t u64_ro, u64_rw;
} inst_t;

static int comp_id;

static void update(void *arg, long period)
{
    inst_t *d = arg;
    *d->bit_out = *d->bit_in;
    *d->float_out = *d->float_in;
    *d->s32_out = *d->s32_in;
    *d->u32_out = *d->u32_in;
    *d->s64_out = *d->s64_in;
    *d->u64_out = *d->u64_in;
    while (*d->hold && !rtapi_sim_yield())
        *d->yields += 1;
    if (*d->spin_every > 0 && *d->calls % *d->spin_every == *d->spin_every - 1 &&
        !rtapi_is_simclock()) {
        long long until = rtapi_get_time() + *d->spin_ns;
        while (rtapi_get_time() < until)
            ;
        *d->spins += 1;
    }
    *d->calls += 1;
    *d->now = rtapi_get_time();
    *d->period = (hal_s32_t)period;
}

#define PINS(T, t)                                                                      \
    if (rc == 0)                                                                        \
        rc = hal_pin_##t##_newf(HAL_IN, &d->t##_in, comp_id, "hm-testmod.%d." #t "-in", i); \
    if (rc == 0)                                                                        \
        rc = hal_pin_##t##_newf(HAL_OUT, &d->t##_out, comp_id, "hm-testmod.%d." #t "-out", i); \
    if (rc == 0)                                                                        \
        rc = hal_pin_##t##_newf(HAL_IO, &d->t##_io, comp_id, "hm-testmod.%d." #t "-io", i); \
    if (rc == 0)                                                                        \
        rc = hal_param_##t##_newf(HAL_RO, &d->t##_ro, comp_id, "hm-testmod.%d." #t "-ro", i); \
    if (rc == 0)                                                                        \
        rc = hal_param_##t##_newf(HAL_RW, &d->t##_rw, comp_id, "hm-testmod.%d." #t "-rw", i);

int rtapi_app_main(void)
{
    if (count < 1 || count > 16) {
        rtapi_print_msg(RTAPI_MSG_ERR, "HM_TESTMOD: ERROR: count=%d out of range 1..16\n", count);
        return -EINVAL;
    }
    if (verbose)
        rtapi_print_msg(RTAPI_MSG_INFO, "HM_TESTMOD: loading %d instance(s)\n", count);
    rtapi_print_msg(RTAPI_MSG_DBG, "HM_TESTMOD: label=%s values=%ld,%ld,%ld,%ld\n", label,
                    values[0], values[1], values[2], values[3]);
    comp_id = hal_init("hm_testmod");
    if (comp_id < 0)
        return comp_id;
    inst_t *all = hal_malloc((long)sizeof(inst_t) * count);
    if (all == NULL) {
        hal_exit(comp_id);
        return -ENOMEM;
    }
    for (int i = 0; i < count; i++) {
        inst_t *d = &all[i];
        int rc = 0;
        PINS(BIT, bit)
        PINS(FLOAT, float)
        PINS(S32, s32)
        PINS(U32, u32)
        PINS(S64, s64)
        PINS(U64, u64)
        if (rc == 0)
            rc = hal_pin_u32_newf(HAL_OUT, &d->calls, comp_id, "hm-testmod.%d.calls", i);
        if (rc == 0)
            rc = hal_pin_s64_newf(HAL_OUT, &d->now, comp_id, "hm-testmod.%d.now", i);
        if (rc == 0)
            rc = hal_pin_bit_newf(HAL_IN, &d->hold, comp_id, "hm-testmod.%d.hold", i);
        if (rc == 0)
            rc = hal_pin_u32_newf(HAL_OUT, &d->yields, comp_id, "hm-testmod.%d.yields", i);
        if (rc == 0)
            rc = hal_pin_s32_newf(HAL_OUT, &d->period, comp_id, "hm-testmod.%d.period", i);
        if (rc == 0)
            rc = hal_pin_u32_newf(HAL_IN, &d->spin_every, comp_id, "hm-testmod.%d.spin-every", i);
        if (rc == 0)
            rc = hal_pin_s32_newf(HAL_IN, &d->spin_ns, comp_id, "hm-testmod.%d.spin-ns", i);
        if (rc == 0)
            rc = hal_pin_u32_newf(HAL_OUT, &d->spins, comp_id, "hm-testmod.%d.spins", i);
        if (rc == 0)
            rc = hal_export_functf(update, d, 1, 0, comp_id, "hm-testmod.%d.update", i);
        if (rc != 0) {
            hal_exit(comp_id);
            return rc;
        }
        d->float_ro = 1.5;
        d->s32_ro = -7;
        d->u32_ro = 7;
    }
    if (fail) {
        rtapi_print_msg(RTAPI_MSG_ERR, "HM_TESTMOD: ERROR: failing on purpose (fail=1)\n");
        return -EINVAL; /* rtapi_app removes what we created */
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void) { hal_exit(comp_id); }
