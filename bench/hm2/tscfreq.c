/* SPDX-License-Identifier: GPL-2.0-or-later */
/* tscfreq: clocks per second of rtapi_get_clocks() (the time-stamp counter
 * on x86, ns elsewhere), measured against CLOCK_MONOTONIC over 200 ms, so
 * bench/hm2 can turn HAL's function .time (clocks) into microseconds. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <time.h>

static long long clocks(void)
{
#if defined(__x86_64__) || defined(__i386__)
    unsigned int lo, hi;
    __asm__ __volatile__("rdtsc" : "=a"(lo), "=d"(hi));
    return ((long long)hi << 32) | lo;
#else
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long long)ts.tv_sec * 1000000000LL + ts.tv_nsec;
#endif
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

int main(void)
{
    double t0 = now();
    long long c0 = clocks();
    struct timespec d = {0, 200000000};
    nanosleep(&d, NULL);
    double t1 = now();
    long long c1 = clocks();
    printf("%.0f\n", (double)(c1 - c0) / (t1 - t0));
    return 0;
}
