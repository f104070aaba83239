/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_bench - EPP traffic and time per servo cycle of the pluto_servo and
 * pluto_step drivers (their read + write functions, unchanged).
 *
 *   pluto_bench [--cycles N] [--narrow] [--port SPEC --servo-fw FILE --step-fw FILE]
 *
 * Without --port the drivers run against the register model of the unit
 * tests behind a batching port (counts only; host time is the driver's own
 * cost).  With --port (e.g. sim:/tmp/vb.sock, a virtual Pluto) the firmware
 * is uploaded first and the wall time per cycle includes the round trips.
 * EPP bus time is the cycle count at the PC-port rate of 1 us per cycle.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fakes.h"
#include "pluto_drivers.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static hal_float_t f_pins[64];
static hal_s32_t s_pins[16];
static hal_bit_t b_pins[128];

static void report(const char *drv, epp_port_t *port, int n, double wall, double worst)
{
    const struct epp_counters *c = &port->count;
    double per = 1.0 / n;
    double cycles = (double)(c->addr_cycles + c->data_cycles) * per;
    printf("%s: per servo cycle (read + write): %.0f address + %.0f data cycles, %.0f status "
           "reads, %.0f port I/O instructions (%s), %.0f round trips\n",
           drv, (double)c->addr_cycles * per, (double)c->data_cycles * per,
           (double)c->reg_accesses * per, (double)c->port_ios * per,
           port->wide ? "epp_wide" : "byte I/O", (double)c->flushes * per);
    printf("%s: EPP bus time per servo cycle: %.1f us at 1 us per EPP cycle "
           "(anchor: LinuxCNC ~100 us per cycle on real ports, ~1 us per EPP cycle)\n",
           drv, cycles + (double)c->reg_accesses * per);
    printf("%s: host time per servo cycle on %s: mean %.2f us, worst %.2f us over %d cycles\n",
           drv, port->name, wall * 1e6 * per, worst * 1e6, n);
}

static int open_port(epp_port_t *port, struct pcport *pc, const char *spec, int wide,
                     const char *fw, const char *board)
{
    if (!spec) {
        fake_batch_open(port, pc, wide);
        return 0;
    }
    char err[256], path[1024];
    uint8_t *img = NULL;
    size_t len = 0;
    int r = pluto_read_firmware(fw, &img, &len, path, sizeof(path), err, sizeof(err));
    if (r) {
        fprintf(stderr, "pluto_bench: %s\n", err);
        return r;
    }
    r = epp_port_open(port, spec, 0, 0, wide, err, sizeof(err));
    if (r) {
        fprintf(stderr, "pluto_bench: %s\n", err);
        free(img);
        return r;
    }
    r = pluto_upload(port, img, len, NULL);
    free(img);
    if (!r)
        r = pluto_probe(port, board, NULL);
    if (r) {
        fprintf(stderr, "pluto_bench: %s firmware %s did not come up on %s\n", board, fw, spec);
        epp_port_close(port);
    }
    return r;
}

int main(int argc, char **argv)
{
    int n = 20000, wide = 1;
    const char *spec = NULL, *servo_fw = "pluto_servo.rbf", *step_fw = "pluto_step.rbf";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--cycles") && i + 1 < argc)
            n = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--narrow"))
            wide = 0;
        else if (!strcmp(argv[i], "--port") && i + 1 < argc)
            spec = argv[++i];
        else if (!strcmp(argv[i], "--servo-fw") && i + 1 < argc)
            servo_fw = argv[++i];
        else if (!strcmp(argv[i], "--step-fw") && i + 1 < argc)
            step_fw = argv[++i];
        else {
            fprintf(stderr, "usage: pluto_bench [--cycles N] [--narrow] [--port SPEC "
                            "--servo-fw FILE --step-fw FILE]\n");
            return 2;
        }
    }
    if (n <= 0)
        n = 1;
    static struct periph P;
    static struct pcport PC;
    epp_port_t port;

    /* ---- pluto_servo ---- */
    periph_init(&P, PERIPH_PLUTO);
    P.trace_on = 0;
    pcport_init(&PC, &P);
    PC.log_on = 0;
    if (open_port(&port, &PC, spec, wide, servo_fw, "pluto-servo"))
        return 1;
    static struct pluto_servo s;
    memset(&s, 0, sizeof(s));
    for (int i = 0; i < 4; i++) {
        s.enc_count[i] = &s_pins[i];
        s.enc_position[i] = &f_pins[i];
        s.enc_velocity[i] = &f_pins[4 + i];
        s.enc_reset[i] = &b_pins[i];
        s.enc_index_enable[i] = &b_pins[4 + i];
        s.pwm_value[i] = &f_pins[8 + i];
        s.pwm_enable[i] = &b_pins[8 + i];
        *s.pwm_enable[i] = 1;
    }
    for (int i = 0; i < 20; i++) {
        s.dout[i] = &b_pins[16 + i];
        s.din[i] = &b_pins[40 + i];
        s.din_not[i] = &b_pins[64 + i];
    }
    pluto_servo_defaults(&s);
    s.port = &port;
    s.watchdog = 1;
    epp_counters_reset(&port);
    double worst = 0, t0 = now_s();
    for (int k = 0; k < n; k++) {
        double a = now_s();
        *s.pwm_value[0] = (k % 200) / 100.0 - 1.0;
        pluto_servo_read(&s, 1000000);
        pluto_servo_write(&s, 1000000);
        double d = now_s() - a;
        if (d > worst)
            worst = d;
    }
    double wall = now_s() - t0;
    if (s.communication_error)
        printf("pluto_servo: %u communication errors during the run!\n",
               (unsigned)s.communication_error);
    report("pluto_servo", &port, n, wall, worst);
    epp_port_close(&port);

    /* ---- pluto_step ---- */
    periph_init(&P, PERIPH_PLUTO);
    P.trace_on = 0;
    P.pluto_step = 1;
    pcport_init(&PC, &P);
    PC.log_on = 0;
    if (open_port(&port, &PC, spec, wide, step_fw, "pluto-step"))
        return 1;
    static struct pluto_step t;
    memset(&t, 0, sizeof(t));
    for (int i = 0; i < 4; i++) {
        t.position_cmd[i] = &f_pins[16 + i];
        t.velocity_fb[i] = &f_pins[20 + i];
        t.position_fb[i] = &f_pins[24 + i];
        t.counts[i] = &s_pins[8 + i];
        t.enable[i] = &b_pins[90 + i];
        t.reset[i] = &b_pins[94 + i];
        *t.enable[i] = 1;
    }
    for (int i = 0; i < 14; i++)
        t.dout[i] = &b_pins[100 + i];
    for (int i = 0; i < 16; i++) {
        t.din[i] = &b_pins[40 + i];
        t.din_not[i] = &b_pins[64 + i];
    }
    pluto_step_defaults(&t);
    t.port = &port;
    t.watchdog = 1;
    epp_counters_reset(&port);
    worst = 0;
    t0 = now_s();
    for (int k = 0; k < n; k++) {
        double a = now_s();
        *t.position_cmd[0] = k * 1e-3;
        pluto_step_read(&t, 1000000);
        pluto_step_write(&t, 1000000);
        double d = now_s() - a;
        if (d > worst)
            worst = d;
    }
    wall = now_s() - t0;
    if (t.communication_error)
        printf("pluto_step: %u communication errors during the run!\n",
               (unsigned)t.communication_error);
    report("pluto_step", &port, n, wall, worst);
    epp_port_close(&port);
    return 0;
}
