/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * scope_cost: scope_rt's scope.sample called in a tight loop, to measure
 * its cost per sample more finely than THREAD.time can (the time-stamp
 * counter of a virtual machine may tick in steps of tens of clocks).
 *
 * A realtime module (loadrt scope_cost after loadrt scope_rt): in
 * rtapi_app, where scope.sample runs, it makes 13 pins of every type (6 of
 * them linked to signals) and 2 signals, takes scope.sample's address and
 * argument from the HAL function table, configures the scope through
 * libhalview as halscope does, and calls the function n times per
 * configuration: idle (not armed), armed with 16 channels waiting for a
 * trigger that never comes, roll with 16 channels (the ring drained every
 * 1000 calls), armed with 1 channel.  It prints ns per call for each and
 * then fails its load on purpose, so it leaves nothing behind.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hal.h"
#include "hal_query.h"
#include "halview.h"
#include "rtapi.h"

static long calls = 2000000;
RTAPI_MP_LONG(calls, "calls per configuration");

typedef void (*funct_t)(void *, long);

/* CPU time of this thread: other processes on the machine do not count. */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int make_pins(int comp)
{
    static const hal_type_t types[] = {HAL_FLOAT, HAL_BIT, HAL_S32, HAL_U32, HAL_S64, HAL_U64};
    void **ptrs = hal_malloc(13 * sizeof(void *));
    if (ptrs == NULL)
        return -1;
    for (int i = 0; i < 13; i++) {
        char name[64];
        snprintf(name, sizeof(name), "bench.p%02d", i);
        if (hal_pin_new(name, types[i % 6], HAL_IN, &ptrs[i], comp) < 0)
            return -1;
    }
    for (int i = 0; i < 8; i++) {
        char sig[32], pin[32];
        snprintf(sig, sizeof(sig), "bs%d", i);
        snprintf(pin, sizeof(pin), "bench.p%02d", i);
        if (hal_signal_new(sig, types[i % 6]) < 0 || (i < 6 && hal_link(pin, sig) < 0))
            return -1;
    }
    return 0;
}

static double run(funct_t f, void *arg, hv_scope_t *h, long n, int drain)
{
    f(arg, 100000); /* takes the pending command */
    double t0 = now();
    for (long i = 0; i < n; i++) {
        f(arg, 100000);
        if (drain && i % 1000 == 999) {
            hv_scope_status_t st;
            hv_scope_status(h, &st);
            hv_scope_consume(h, (uint64_t)st.widx);
        }
    }
    return (now() - t0) / (double)n * 1e9;
}

static int configure(hv_scope_t *h, int nchan, int mode)
{
    char err[256];
    for (int i = 0; i < nchan; i++) {
        char name[32];
        int kind = HV_PIN;
        if (i < 13)
            snprintf(name, sizeof(name), "bench.p%02d", i);
        else if (i < 15)
            snprintf(name, sizeof(name), "bs%d", i - 7), kind = HV_SIG;
        else
            snprintf(name, sizeof(name), "bench.p00"), kind = HV_PIN;
        if (hv_scope_set_chan(h, i, kind, name, err, sizeof(err)) < 0) {
            rtapi_print("scope_cost: %s\n", err);
            return -1;
        }
    }
    if (hv_scope_arm(h, nchan, 1, 16000 / (uint64_t)nchan, 0, 0, 0, 1e300, mode, 0, err,
                     sizeof(err)) < 0) {
        rtapi_print("scope_cost: %s\n", err);
        return -1;
    }
    return 0;
}

int rtapi_app_main(void)
{
    int comp = hal_init("scope_cost");
    if (comp < 0 || make_pins(comp) < 0 || hal_ready(comp) < 0) {
        rtapi_print("scope_cost: cannot set up the bench's pins\n");
        return -EINVAL;
    }
    hal_q_funct_t fi;
    char err[256];
    hv_scope_t *h = hv_scope_open(err, sizeof(err));
    if (hal_q_funct("scope.sample", &fi) < 0 || h == NULL) {
        rtapi_print("scope_cost: scope.sample not found (%s)\n", err);
        hal_exit(comp);
        return -EINVAL;
    }
    funct_t f = (funct_t)(uintptr_t)fi.code_addr;
    void *arg = (void *)(uintptr_t)fi.arg;
    double idle = run(f, arg, h, calls, 0);
    double armed16 = configure(h, 16, 0) < 0 ? -1 : run(f, arg, h, calls, 0);
    double roll16 = configure(h, 16, 3) < 0 ? -1 : run(f, arg, h, calls, 1);
    double armed1 = configure(h, 1, 0) < 0 ? -1 : run(f, arg, h, calls, 0);
    hv_scope_stop(h);
    f(arg, 100000);
    rtapi_print("scope_cost: %.1f %.1f %.1f %.1f\n", idle, armed16, roll16, armed1);
    hv_scope_close(h);
    hal_exit(comp);
    return -ECANCELED; /* measured; leave nothing loaded */
}

void rtapi_app_exit(void) {}
