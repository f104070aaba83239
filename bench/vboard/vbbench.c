/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * vboard-bench - speed figures of the virtual board (bench/vboard/run.sh).
 *
 *   vboard-bench SOCKET speed MS [steps]   simulated ClockLow cycles per
 *                                          wall second over MS ms of board
 *                                          time (steps: 4 stepgens running;
 *                                          active: every module at work)
 *   vboard-bench SOCKET servo N [ADV_NS]   N servo cycles of a 5i20 SVST8_4
 *                                          read list + write list (the
 *                                          registers hm2 touches per period),
 *                                          host time advancing ADV_NS per
 *                                          cycle (0: no advance); prints the
 *                                          median and mean wall time per
 *                                          read+write pair
 *   vboard-bench SOCKET hello N            protocol round trip alone
 *   vboard-bench pingpong N                the machine's process-to-process
 *                                          socket round trip (the floor)
 *
 * It uses the project's C client (vbclient), as the hm2_sim driver does.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "vboard_client.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int put_xfer(vbc_t *c, uint32_t addr, uint32_t size)
{
    struct vb_xfer x = {addr, size};
    return vbc_req_put(c, &x, sizeof x);
}

static int write_regs(vbc_t *c, uint32_t addr, const uint32_t *w, uint32_t n)
{
    vbc_req_start(c);
    int rc = put_xfer(c, addr, 4 * n);
    if (rc == 0)
        rc = vbc_req_put(c, w, 4 * n);
    if (rc == 0)
        rc = vbc_send(c, VB_WRITE, 0);
    return rc;
}

/* Four stepgens stepping fast (SVST8_4: StepGen base 0x2000). */
static int start_stepgens(vbc_t *c)
{
    const uint32_t zero4[4] = {0, 0, 0, 0}, two4[4] = {2, 2, 2, 2};
    const uint32_t rates[4] = {1u << 29, 3u << 28, 1u << 30, 5u << 27};
    const uint32_t dds = 0xFFFFFFFFu, alt = 0xFFFFFF, ddr = 0xFFFFFF;
    int rc = write_regs(c, 0x1208, &alt, 1);
    rc = rc ? rc : write_regs(c, 0x1108, &ddr, 1);
    rc = rc ? rc : write_regs(c, 0x2200, zero4, 4);
    rc = rc ? rc : write_regs(c, 0x2300, two4, 4);
    rc = rc ? rc : write_regs(c, 0x2400, two4, 4);
    rc = rc ? rc : write_regs(c, 0x2500, two4, 4);
    rc = rc ? rc : write_regs(c, 0x2600, two4, 4);
    rc = rc ? rc : write_regs(c, 0x2000, rates, 4);
    rc = rc ? rc : write_regs(c, 0x2900, &dds, 1);
    return rc;
}

/* Every SVST8_4 module at work, at rates a machine uses: 4 stepgens at
 * 100/60/30/10 k steps/s (2 us pulses, 2 us idle, 1 us dir setup/hold), 8
 * PWMs at 20 kHz (12 bits, different duties), the IOPort routing all of
 * them to their pins; the encoders count what the command line's --quad
 * sources feed them (bench/vboard/run.sh). */
static int start_active(vbc_t *c)
{
    const uint32_t widths[4] = {66, 66, 66, 66}, setup[4] = {33, 33, 33, 33};
    const uint32_t rates[4] = {12884901u, 7730941u, 3865470u, 1288490u};
    const uint32_t dds = 0xFFFFFFFFu, alt = 0xFFFFFF, ddr_pwm = 0xFC0FC0, ddr_sg = 0xFFFFFF;
    const uint32_t pwmrate = 53687, enable = 0xFF;
    uint32_t vals[8], modes[8];
    for (int i = 0; i < 8; i++) {
        vals[i] = (uint32_t)(400 + 450 * i) << 16 | (i % 2 ? 0x80000000u : 0);
        modes[i] = 3; /* 12 bits, sawtooth, PWM/Dir */
    }
    int rc = 0;
    for (uint32_t port = 0; port < 3 && rc == 0; port++) {
        uint32_t ddr = port == 2 ? ddr_sg : ddr_pwm;
        rc = write_regs(c, 0x1200 + 4 * port, &alt, 1);
        rc = rc ? rc : write_regs(c, 0x1100 + 4 * port, &ddr, 1);
    }
    rc = rc ? rc : write_regs(c, 0x2500, widths, 4);
    rc = rc ? rc : write_regs(c, 0x2600, widths, 4);
    rc = rc ? rc : write_regs(c, 0x2300, setup, 4);
    rc = rc ? rc : write_regs(c, 0x2400, setup, 4);
    rc = rc ? rc : write_regs(c, 0x2000, rates, 4);
    rc = rc ? rc : write_regs(c, 0x2900, &dds, 1);
    rc = rc ? rc : write_regs(c, 0x4100, modes, 8);
    rc = rc ? rc : write_regs(c, 0x4000, vals, 8);
    rc = rc ? rc : write_regs(c, 0x4200, &pwmrate, 1);
    rc = rc ? rc : write_regs(c, 0x4400, &enable, 1);
    return rc;
}

static int bench_speed(vbc_t *c, double ms, int steps)
{
    struct vb_hello h;
    int rc = vbc_hello(c, &h);
    if (rc < 0 || h.clock_low_hz == 0) {
        fprintf(stderr, "vboard-bench: board not configured or unreachable: %s\n", c->err);
        return 1;
    }
    if (steps && (rc = steps == 2 ? start_active(c) : start_stepgens(c)) < 0) {
        fprintf(stderr, "vboard-bench: programming the stepgens failed: %s\n", c->err);
        return 1;
    }
    struct vb_time t = {VB_TIME_ADVANCE, 0, (uint64_t)(ms * 1e6)};
    uint64_t b0 = c->board_time_ns;
    double w0 = now_s();
    rc = vbc_call(c, VB_TIME, 0, &t, sizeof t);
    double w = now_s() - w0;
    if (rc < 0) {
        fprintf(stderr, "vboard-bench: advance failed: %s\n", c->err);
        return 1;
    }
    double cycles = (double)(c->board_time_ns - b0) * 1e-9 * h.clock_low_hz;
    printf("%.3f M ClockLow cycles/s (%.0f cycles in %.3f s wall, %.1f%% of real time)\n",
           cycles / w * 1e-6, cycles, w, cycles / w / h.clock_low_hz * 100.0);
    return 0;
}

static int cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The registers the hostmot2 driver reads and writes every servo period on
 * SVST8_4 with 8 encoders, 8 PWMs, 4 stepgens, 3 ioports and the
 * watchdog: one READ and one WRITE request (its TRAM lists). */
static int servo_cycle(vbc_t *c, uint64_t host_time, const uint32_t *wdata)
{
    vbc_req_start(c);
    put_xfer(c, 0x3000, 32); /* encoder counts */
    put_xfer(c, 0x3100, 32); /* encoder latch/control */
    put_xfer(c, 0x2100, 16); /* stepgen accumulators */
    put_xfer(c, 0x1000, 12); /* ioport data */
    put_xfer(c, 0x0D00, 4);  /* watchdog status */
    int rc = vbc_send(c, VB_READ, host_time);
    if (rc < 0)
        return rc;
    vbc_req_start(c);
    put_xfer(c, 0x4000, 32); /* pwm values */
    vbc_req_put(c, wdata, 32);
    put_xfer(c, 0x2000, 16); /* stepgen rates */
    vbc_req_put(c, wdata + 8, 16);
    put_xfer(c, 0x1000, 12); /* ioport data */
    vbc_req_put(c, wdata + 12, 12);
    put_xfer(c, 0x0E00, 4);  /* watchdog reset */
    vbc_req_put(c, wdata + 15, 4);
    return vbc_send(c, VB_WRITE, host_time);
}

static int bench_servo(vbc_t *c, int n, uint64_t adv)
{
    uint32_t wdata[16] = {0};
    double *t = calloc((size_t)n, sizeof *t);
    if (!t) {
        fprintf(stderr, "vboard-bench: out of memory for %d samples\n", n);
        return 1;
    }
    uint64_t host = adv ? 1000000000ull : 0;
    if (adv && vbc_call(c, VB_HELLO, host, NULL, 0) < 0) { /* take the epoch */
        fprintf(stderr, "vboard-bench: %s\n", c->err);
        free(t);
        return 1;
    }
    double sum = 0;
    for (int i = 0; i < n; i++) {
        host += adv;
        wdata[0] = (uint32_t)i;
        double w0 = now_s();
        int rc = servo_cycle(c, host, wdata);
        t[i] = now_s() - w0;
        if (rc < 0) {
            fprintf(stderr, "vboard-bench: servo cycle %d failed: %s\n", i, c->err);
            free(t);
            return 1;
        }
        sum += t[i];
    }
    qsort(t, (size_t)n, sizeof *t, cmp_d);
    printf("%.1f us median, %.1f us mean per read+write (%d cycles, %llu ns advance each)\n",
           t[n / 2] * 1e6, sum / n * 1e6, n, (unsigned long long)adv);
    free(t);
    return 0;
}

static int bench_hello(vbc_t *c, int n)
{
    double w0 = now_s();
    for (int i = 0; i < n; i++)
        if (vbc_call(c, VB_HELLO, 0, NULL, 0) < 0) {
            fprintf(stderr, "vboard-bench: %s\n", c->err);
            return 1;
        }
    printf("%.1f us per HELLO round trip (%d)\n", (now_s() - w0) / n * 1e6, n);
    return 0;
}

/* The machine's floor: a 24-byte ping-pong between two processes over a
 * Unix socketpair, both blocking (what any socket-based board costs). */
static int bench_pingpong(int n)
{
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM, 0, sv) < 0) {
        fprintf(stderr, "vboard-bench: socketpair: %s\n", strerror(errno));
        return 1;
    }
    pid_t pid = fork();
    if (pid < 0) {
        fprintf(stderr, "vboard-bench: fork: %s\n", strerror(errno));
        return 1;
    }
    char buf[24] = {0};
    if (pid == 0) {
        close(sv[0]);
        while (read(sv[1], buf, sizeof buf) == (ssize_t)sizeof buf)
            if (write(sv[1], buf, sizeof buf) != (ssize_t)sizeof buf)
                break;
        _exit(0);
    }
    close(sv[1]);
    double w0 = now_s();
    for (int i = 0; i < n; i++)
        if (write(sv[0], buf, sizeof buf) != (ssize_t)sizeof buf ||
            read(sv[0], buf, sizeof buf) != (ssize_t)sizeof buf) {
            fprintf(stderr, "vboard-bench: ping-pong failed: %s\n", strerror(errno));
            break;
        }
    double w = now_s() - w0;
    close(sv[0]);
    waitpid(pid, NULL, 0);
    printf("%.1f us per process-to-process round trip (%d)\n", w / n * 1e6, n);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "pingpong") == 0)
        return bench_pingpong(atoi(argv[2]) > 0 ? atoi(argv[2]) : 1);
    if (argc < 4) {
        fprintf(stderr, "usage: vboard-bench SOCKET speed MS [steps|active] | servo N [ADV_NS] | hello N\n"
                        "       vboard-bench pingpong N\n");
        return 2;
    }
    vbc_t c;
    if (vbc_open(&c, argv[1]) < 0) {
        fprintf(stderr, "vboard-bench: cannot connect to %s: %s\n", argv[1], c.err);
        return 1;
    }
    c.timeout_ms = 600000;
    /* VBBENCH_SPIN_US: the client busy-polls for its reply that long
     * before sleeping (vbclient's spin_us), like hm2_sim's spin_us=. */
    const char *spin = getenv("VBBENCH_SPIN_US");
    c.spin_us = spin ? atoi(spin) : 0;
    int rc;
    if (strcmp(argv[2], "speed") == 0)
        rc = bench_speed(&c, atof(argv[3]),
                         argc <= 4                          ? 0
                         : strcmp(argv[4], "steps") == 0    ? 1
                         : strcmp(argv[4], "active") == 0   ? 2
                                                            : 0);
    else if (strcmp(argv[2], "servo") == 0)
        rc = bench_servo(&c, atoi(argv[3]) > 0 ? atoi(argv[3]) : 1,
                         argc > 4 ? strtoull(argv[4], NULL, 0) : 0);
    else if (strcmp(argv[2], "hello") == 0)
        rc = bench_hello(&c, atoi(argv[3]) > 0 ? atoi(argv[3]) : 1);
    else {
        fprintf(stderr, "vboard-bench: unknown mode '%s'\n", argv[2]);
        rc = 2;
    }
    vbc_close(&c);
    return rc;
}
