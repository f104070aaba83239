/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_test_usercomp - a userspace HAL component for the HAL core tests.
 *
 *   hal_test_usercomp [NAME [SECONDS]]
 *
 * Creates component NAME (default hal_test_usercomp) with pins NAME.in
 * (float IN) and NAME.out (float OUT), becomes ready, copies in*2 to out
 * every millisecond, and exits after SECONDS (default: until SIGTERM).
 * Exit code 3 when SECONDS was negative (to test loadusr -w return codes).
 */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "hal.h"

static volatile sig_atomic_t stop;
static void on_term(int sig)
{
    (void)sig;
    stop = 1;
}

int main(int argc, char **argv)
{
    const char *name = argc > 1 ? argv[1] : "hal_test_usercomp";
    double secs = argc > 2 ? atof(argv[2]) : -1e9;
    if (secs < 0 && secs > -1e8)
        return 3;
    struct sigaction sa = {0};
    sa.sa_handler = on_term;
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
    int id = hal_init(name);
    if (id < 0)
        return 1;
    hal_float_t **p = hal_malloc(2 * sizeof(hal_float_t *));
    if (p == NULL || hal_pin_float_newf(HAL_IN, &p[0], id, "%s.in", name) ||
        hal_pin_float_newf(HAL_OUT, &p[1], id, "%s.out", name)) {
        hal_exit(id);
        return 1;
    }
    hal_ready(id);
    struct timespec t0, now, ms = {0, 1000000};
    clock_gettime(CLOCK_MONOTONIC, &t0);
    while (!stop) {
        *p[1] = *p[0] * 2;
        nanosleep(&ms, NULL);
        clock_gettime(CLOCK_MONOTONIC, &now);
        if (secs >= 0 && (now.tv_sec - t0.tv_sec) + (now.tv_nsec - t0.tv_nsec) * 1e-9 > secs)
            break;
    }
    hal_exit(id);
    return 0;
}
