/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of the epp_port interface and its direct backends (raw port
 * I/O, ppdev, gpiod) against simulated hardware (fakes.c): instruction and
 * system-call sequences, cycle counters, timeout set/clear, bad input.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "../check.h"
#include "fakes.h"
#include "hm2/epp_port.h"

int epp_gpiod_parse(const char *spec, char *chip, size_t chiplen, unsigned *offsets, int *n,
                    uint32_t *timeout_ns, char *err, size_t errlen);

static struct periph P;
static struct pcport PC;
static struct fake_raw FR;

static int open_raw(epp_port_t *port, int wide, long hi)
{
    char err[200] = "";
    periph_init(&P, PERIPH_MEM);
    pcport_init(&PC, &P);
    memset(&FR, 0, sizeof(FR));
    FR.pc = &PC;
    FR.base = 0x378;
    FR.base_hi = hi < 0 ? 0 : (unsigned long)hi;
    struct epp_raw_io io = fake_raw_io(&FR);
    return epp_raw_open(port, &io, 0x378, hi, wide, err, sizeof(err));
}

static void test_raw_instructions(void)
{
    epp_port_t port;
    CHECK_EQ_INT(open_raw(&port, 1, 0x778), 0);
    CHECK_EQ_INT(FR.perm_on, 2);
    CHECK_EQ_STR(port.name, "raw:0x378");
    uint8_t w[4] = {0x11, 0x22, 0x33, 0x44}, r2[2] = {0}, r4[4] = {0}, r1 = 0;
    CHECK_EQ_INT(epp_addr_write(&port, 0x05), 0);
    CHECK_EQ_INT(epp_data_write(&port, w, 4), 0); /* one outl */
    CHECK_EQ_INT(epp_data_write(&port, w, 2), 0); /* one outw */
    CHECK_EQ_INT(epp_data_write(&port, w, 3), 0); /* three outb */
    CHECK_EQ_INT(epp_ecr_write(&port, 0x80), 0);
    CHECK_EQ_INT(epp_addr_write(&port, 0x05), 0);
    CHECK_EQ_INT(epp_data_read(&port, r4, 4), 0);
    CHECK_EQ_INT(epp_data_read(&port, r2, 2), 0);
    CHECK_EQ_INT(epp_data_read(&port, &r1, 1), 0);
    CHECK_EQ_STR(PC.log, "outb(05,+3) outl(44332211,+4) outw(2211,+4) outb(11,+4) outb(22,+4) "
                         "outb(33,+4) outb(80,+1026) outb(05,+3) inl(+4) inw(+4) inb(+4) ");
    /* memory device: 11 22 33 44 | 11 22 | 11 22 33 from address 5 */
    static const uint8_t want[] = {0x11, 0x22, 0x33, 0x44, 0x11, 0x22, 0x11};
    CHECK(memcmp(r4, want, 4) == 0);
    CHECK(memcmp(r2, want + 4, 2) == 0);
    CHECK_EQ_INT(r1, 0x11);
    CHECK_EQ_INT(PC.ecr, 0x80);
    CHECK_EQ_INT(port.count.addr_cycles, 2);
    CHECK_EQ_INT(port.count.data_cycles, 16);
    CHECK_EQ_INT(port.count.data_reads, 7);
    CHECK_EQ_INT(port.count.port_ios, 2 + 1 + 1 + 3 + 1 + 1 + 1 + 1);
    CHECK_EQ_INT(port.count.reg_accesses, 1);
    CHECK_EQ_INT(port.count.flushes, 0); /* direct: nothing to flush */
    epp_port_close(&port);
    CHECK_EQ_INT(FR.perm_on, 0);
}

static void test_raw_narrow_and_no_ecr(void)
{
    epp_port_t port;
    CHECK_EQ_INT(open_raw(&port, 0, -1), 0);
    CHECK_EQ_INT(FR.perm_on, 1);
    CHECK_EQ_INT(port.has_ecr, 0);
    uint8_t w[4] = {1, 2, 3, 4};
    epp_data_write(&port, w, 4);
    epp_ecr_write(&port, 0x94); /* no ECR: not written */
    CHECK_EQ_STR(PC.log, "outb(01,+4) outb(02,+4) outb(03,+4) outb(04,+4) ");
    CHECK_EQ_INT(PC.ecr_writes, 0);
    epp_port_close(&port);
}

static void test_raw_ioperm_failure(void)
{
    epp_port_t port;
    char err[200] = "";
    periph_init(&P, PERIPH_MEM);
    pcport_init(&PC, &P);
    memset(&FR, 0, sizeof(FR));
    FR.pc = &PC;
    FR.ioperm_fail = 1;
    struct epp_raw_io io = fake_raw_io(&FR);
    CHECK_EQ_INT(epp_raw_open(&port, &io, 0x378, -1, 1, err, sizeof(err)), -EPERM);
    CHECK(strstr(err, "ioperm(0x378, 8) failed") != NULL);
    CHECK(strstr(err, "CAP_SYS_RAWIO") != NULL);
    CHECK_EQ_INT(epp_raw_open(&port, &io, 0, -1, 1, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "bad I/O address") != NULL);
}

static void test_raw_timeout_and_clear(void)
{
    epp_port_t port;
    for (int chip = 0; chip < 2; chip++) {
        CHECK_EQ_INT(open_raw(&port, 1, 0x778), 0);
        PC.clear_on_one = chip;
        P.stall = 1;
        uint8_t b[4];
        epp_addr_write(&port, 0);
        epp_data_read(&port, b, 4);
        CHECK_EQ_INT(b[0], 0xFF);
        CHECK_EQ_INT(epp_timeout(&port), 1);
        PC.log_len = 0;
        PC.log[0] = 0;
        CHECK_EQ_INT(epp_clear_timeout_pluto(&port), 0);
        CHECK_EQ_STR(PC.log, "inb(+1) outb(79,+1) outb(78,+1) ");
        CHECK_EQ_INT(epp_timeout(&port), 0);
        /* the hm2 variant: status read; two reads; two writes; read */
        P.stall = 0;
        epp_data_read(&port, b, 1); /* fine */
        CHECK_EQ_INT(epp_timeout(&port), 0);
        P.stall = 1;
        epp_data_read(&port, b, 1);
        P.stall = 0;
        PC.log_len = 0;
        PC.log[0] = 0;
        CHECK_EQ_INT(epp_clear_timeout_hm2(&port), 0);
        CHECK_EQ_STR(PC.log, "inb(+1) inb(+1) inb(+1) outb(79,+1) outb(78,+1) inb(+1) ");
        /* nothing to clear: one read, one check */
        PC.log_len = 0;
        PC.log[0] = 0;
        CHECK_EQ_INT(epp_clear_timeout_hm2(&port), 0);
        CHECK_EQ_STR(PC.log, "inb(+1) inb(+1) ");
        epp_port_close(&port);
    }
}

static void test_batching_queue(void)
{
    epp_port_t port;
    periph_init(&P, PERIPH_MEM);
    pcport_init(&PC, &P);
    fake_batch_open(&port, &PC, 1);
    fake_batch_executes = 0;
    uint8_t w[8] = {1, 2, 3, 4, 5, 6, 7, 8}, r[8] = {0}, st = 0xAA;
    epp_addr_write(&port, 0x10);
    epp_data_write(&port, w, 8);
    w[0] = 0x99; /* the port copied the data at queue time */
    epp_addr_write(&port, 0x10);
    epp_data_read(&port, r, 8);
    epp_status_read(&port, &st);
    CHECK_EQ_INT(fake_batch_executes, 0);
    CHECK_EQ_INT(P.mem[0x10], 0);
    CHECK_EQ_INT(r[0], 0);
    CHECK_EQ_INT(st, 0xAA);
    CHECK_EQ_INT(epp_flush(&port), 0);
    CHECK_EQ_INT(fake_batch_executes, 1);
    CHECK_EQ_INT(r[0], 1);
    CHECK_EQ_INT(r[7], 8);
    CHECK_EQ_INT(st & 1, 0);
    CHECK_EQ_INT(port.count.flushes, 1);
    CHECK_EQ_INT(port.count.port_ios, 1 + 2 + 1 + 2 + 1);
    CHECK_EQ_INT(port.count.bus_ns, (2 + 16) * 1000 + 1000);
    /* empty flush: no round trip */
    CHECK_EQ_INT(epp_flush(&port), 0);
    CHECK_EQ_INT(fake_batch_executes, 1);
    /* discard */
    epp_addr_write(&port, 0x20);
    epp_discard(&port);
    CHECK_EQ_INT(epp_flush(&port), 0);
    CHECK_EQ_INT(fake_batch_executes, 1);
    /* many ops grow the queue */
    for (int i = 0; i < 5000; i++)
        epp_data_write8(&port, w, 1);
    CHECK_EQ_INT(port.n_ops, 5000);
    CHECK_EQ_INT(epp_flush(&port), 0);
    epp_counters_reset(&port);
    CHECK_EQ_INT(port.count.data_cycles, 0);
    epp_port_close(&port);
}

static void test_bad_arguments(void)
{
    epp_port_t port;
    uint8_t b;
    CHECK_EQ_INT(epp_addr_write(NULL, 0), -EINVAL);
    periph_init(&P, PERIPH_MEM);
    pcport_init(&PC, &P);
    fake_batch_open(&port, &PC, 0);
    CHECK_EQ_INT(epp_data_read(&port, NULL, 4), -EINVAL);
    CHECK_EQ_INT(epp_status_read(&port, NULL), -EINVAL);
    CHECK_EQ_INT(epp_addr_read(&port, NULL), -EINVAL);
    CHECK_EQ_INT(epp_data_read(&port, &b, 0), 0);
    CHECK_EQ_INT(port.n_ops, 0);
    epp_port_close(&port);
    CHECK_EQ_INT(epp_flush(&port), -EINVAL); /* closed port */
}

static void test_open_specs(void)
{
    epp_port_t port;
    char err[256];
    CHECK_EQ_INT(epp_port_open(&port, "bogus:1", 0, 0, 1, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "unknown port kind") != NULL);
    CHECK_EQ_INT(epp_port_open(&port, "raw:zzz", 0, 0, 1, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "bad I/O address 'zzz'") != NULL);
    CHECK_EQ_INT(epp_port_open(&port, "raw:0x378,nope", 0, 0, 1, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "bad ECR base") != NULL);
    CHECK_EQ_INT(epp_port_open(&port, "ppdev:", 0, 0, 1, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "missing device path") != NULL);
    CHECK_EQ_INT(epp_port_open(&port, "sim:", 0, 0, 1, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "missing socket path") != NULL);
    CHECK(epp_port_open(&port, "ppdev:/nonexistent/parport9", 0, 0, 1, err, sizeof(err)) < 0);
    CHECK(strstr(err, "/nonexistent/parport9: open failed") != NULL);
    CHECK_EQ_INT(epp_port_open(&port, NULL, -5, 0, 1, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "ioaddr=-5") != NULL);
    CHECK_EQ_INT(epp_port_open(&port, "", 9, 0, 1, err, sizeof(err)), -ENODEV);
    CHECK(strstr(err, "parport9") != NULL);
    CHECK(epp_port_open(&port, "gpiod:gpiochip0:1/2/3", 0, 0, 1, err, sizeof(err)) < 0);
    CHECK(strstr(err, "need 12 line offsets") != NULL);
}

static void test_gpiod_parse(void)
{
    char chip[64], err[256];
    unsigned off[13];
    int n;
    uint32_t to = 10000;
    CHECK_EQ_INT(epp_gpiod_parse("gpiochip3:lines=0/1/2/3/4/5/6/7/8/9/10/11:timeout_us=50",
                                 chip, sizeof(chip), off, &n, &to, err, sizeof(err)),
                 0);
    CHECK_EQ_STR(chip, "gpiochip3");
    CHECK_EQ_INT(n, 12);
    CHECK_EQ_INT(off[11], 11);
    CHECK_EQ_INT(to, 50000);
    CHECK_EQ_INT(epp_gpiod_parse("gpiochip0:20,21,22,23,24,25,26,27,4,5,6,17,18", chip,
                                 sizeof(chip), off, &n, &to, err, sizeof(err)),
                 0);
    CHECK_EQ_INT(n, 13);
    CHECK_EQ_INT(off[12], 18);
    CHECK_EQ_INT(epp_gpiod_parse("gpiochip0:lines=0/1/2/3/4/5/6/7/8/9/10/10", chip, sizeof(chip),
                                 off, &n, &to, err, sizeof(err)),
                 -EINVAL);
    CHECK(strstr(err, "line 10 used twice (nAddrStr and nWait)") != NULL);
    CHECK_EQ_INT(epp_gpiod_parse("gpiochip0:lines=0/1/x", chip, sizeof(chip), off, &n, &to, err,
                                 sizeof(err)),
                 -EINVAL);
    CHECK(strstr(err, "bad line offset 'x'") != NULL);
    CHECK_EQ_INT(epp_gpiod_parse("gpiochip0:lines=0/1/2/3/4/5/6/7/8/9/10/11:timeout_us=0", chip,
                                 sizeof(chip), off, &n, &to, err, sizeof(err)),
                 -EINVAL);
    CHECK(strstr(err, "bad timeout_us") != NULL);
    CHECK_EQ_INT(epp_gpiod_parse(":lines=1", chip, sizeof(chip), off, &n, &to, err, sizeof(err)),
                 -EINVAL);
    CHECK_EQ_INT(epp_gpiod_parse("c:0/1/2/3/4/5/6/7/8/9/10/11:extra", chip, sizeof(chip), off, &n,
                                 &to, err, sizeof(err)),
                 -EINVAL);
    CHECK(strstr(err, "unknown option 'extra'") != NULL);
}

/* ---- ppdev -------------------------------------------------------------- */

static void test_ppdev(void)
{
    struct fake_ppdev f;
    epp_port_t port;
    char err[256];
    periph_init(&P, PERIPH_MEM);
    pcport_init(&PC, &P);
    memset(&f, 0, sizeof(f));
    f.pc = &PC;
    struct epp_ppdev_sys sys = fake_ppdev_sys(&f);
    CHECK_EQ_INT(epp_ppdev_open(&port, &sys, "/dev/parport0", 1, err, sizeof(err)), 0);
    CHECK_EQ_STR(f.calls, "open(/dev/parport0,rw) PPCLAIM PPSETMODE(EPP) PPSETFLAGS(FAST) ");
    f.calls_len = 0;
    f.calls[0] = 0;
    uint8_t w[4] = {9, 8, 7, 6}, r[4] = {0}, st;
    epp_addr_write(&port, 0x40);
    epp_data_write(&port, w, 4);
    epp_addr_write(&port, 0x40);
    epp_data_read(&port, r, 4);
    epp_status_read(&port, &st);
    CHECK_EQ_STR(f.calls, "PPSETMODE(EPP|ADDR) writeA(1) PPSETMODE(EPP) write(4) "
                          "PPSETMODE(EPP|ADDR) writeA(1) PPSETMODE(EPP) read(4) PPRSTATUS ");
    CHECK(memcmp(r, w, 4) == 0);
    CHECK_EQ_INT(st & 1, 0);
    /* short read = timeout; sticky until a status write; no cycles meanwhile */
    P.stall = 1;
    epp_data_read(&port, r, 4);
    CHECK_EQ_INT(r[0], 0xFF);
    CHECK_EQ_INT(epp_timeout(&port), 1);
    P.stall = 0;
    f.calls_len = 0;
    f.calls[0] = 0;
    epp_data_write(&port, w, 4);
    CHECK_EQ_STR(f.calls, ""); /* blocked by the timeout bit */
    CHECK_EQ_INT(epp_clear_timeout_pluto(&port), 0);
    CHECK_EQ_INT(epp_timeout(&port), 0);
    /* SPP registers */
    f.calls_len = 0;
    f.calls[0] = 0;
    epp_control_write(&port, 0x05);
    epp_spp_data_write(&port, 0xFF);
    epp_ecr_write(&port, 0x00);
    CHECK_EQ_STR(f.calls, "PPWCONTROL(05) PPDATADIR(0) PPWDATA(ff) ");
    epp_port_close(&port);
    CHECK_EQ_INT(f.released, 1);
    CHECK_EQ_INT(f.closed, 1);

    /* failures name the device and the reason, and undo what was done */
    memset(&f, 0, sizeof(f));
    f.pc = &PC;
    f.claim_fail = 1;
    CHECK_EQ_INT(epp_ppdev_open(&port, &sys, "/dev/parport1", 0, err, sizeof(err)), -EBUSY);
    CHECK(strstr(err, "ppdev /dev/parport1: PPCLAIM failed") != NULL);
    CHECK_EQ_INT(f.closed, 1);
    memset(&f, 0, sizeof(f));
    f.pc = &PC;
    f.mode_fail = 1;
    CHECK_EQ_INT(epp_ppdev_open(&port, &sys, "/dev/parport1", 0, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "PPSETMODE EPP failed") != NULL);
    CHECK_EQ_INT(f.released, 1);
    CHECK_EQ_INT(f.closed, 1);
    memset(&f, 0, sizeof(f));
    f.pc = &PC;
    f.open_fail = 1;
    CHECK_EQ_INT(epp_ppdev_open(&port, &sys, "/dev/parport1", 0, err, sizeof(err)), -ENOENT);
    CHECK(strstr(err, "open failed") != NULL);
}

/* ---- gpiod -------------------------------------------------------------- */

static void test_gpiod_cycles(void)
{
    struct fake_lines f;
    epp_port_t port;
    char err[256];
    for (int delay = 0; delay < 3; delay += 2) {
        periph_init(&P, PERIPH_MEM);
        memset(&f, 0, sizeof(f));
        f.p = &P;
        f.ack_delay = delay;
        struct epp_gpio_lines l = fake_gpio_lines(&f, 0);
        CHECK_EQ_INT(epp_gpiod_open(&port, &l, 10000, "gpiod:test", err, sizeof(err)), 0);
        CHECK_EQ_STR(port.backend->kind, "gpiod");
        uint8_t w[6] = {0x5A, 0xA5, 0x00, 0xFF, 0x12, 0x34}, r[6] = {0};
        epp_addr_write(&port, 0x30);
        epp_data_write(&port, w, 6);
        epp_addr_write(&port, 0x30);
        epp_data_read(&port, r, 6);
        CHECK(memcmp(r, w, 6) == 0);
        CHECK(memcmp(P.mem + 0x30, w, 6) == 0);
        uint8_t a = 0;
        epp_addr_read(&port, &a);
        CHECK_EQ_INT(a, 0x36);
        CHECK_EQ_INT(f.bus_conflicts, 0);
        CHECK_EQ_INT(epp_timeout(&port), 0);
        CHECK_EQ_STR(P.trace, "A(30) W(5a) W(a5) W(00) W(ff) W(12) W(34) A(30) R(5a) R(a5) "
                              "R(00) R(ff) R(12) R(34) a(36) ");
        /* idle bus afterwards: strobes and nWrite high */
        CHECK_EQ_INT(f.level[EPP_GPIO_NWRITE], 1);
        CHECK_EQ_INT(f.level[EPP_GPIO_NDATASTR], 1);
        CHECK_EQ_INT(f.level[EPP_GPIO_NADDRSTR], 1);
        epp_port_close(&port);
        CHECK_EQ_INT(f.closed, 1);
    }
}

static void test_gpiod_timeout(void)
{
    struct fake_lines f;
    epp_port_t port;
    char err[256];
    periph_init(&P, PERIPH_MEM);
    memset(&f, 0, sizeof(f));
    f.p = &P;
    struct epp_gpio_lines l = fake_gpio_lines(&f, 0);
    CHECK_EQ_INT(epp_gpiod_open(&port, &l, 10000, "gpiod:test", err, sizeof(err)), 0);
    P.stall = 1;
    uint8_t r[2] = {0, 0};
    uint64_t t0 = f.t;
    epp_data_read(&port, r, 2);
    CHECK_EQ_INT(r[0], 0xFF);
    CHECK_EQ_INT(r[1], 0xFF);
    /* gave up after ~10 us of polling, only once (then blocked) */
    CHECK(f.t - t0 >= 10000 && f.t - t0 < 12000);
    CHECK_EQ_INT(f.level[EPP_GPIO_NDATASTR], 1); /* strobe released */
    uint8_t st = 0;
    epp_status_read(&port, &st);
    CHECK_EQ_INT(st & 1, 1);
    P.stall = 0;
    epp_clear_timeout_pluto(&port);
    CHECK_EQ_INT(epp_timeout(&port), 0);
    epp_addr_write(&port, 1);
    CHECK(strstr(P.trace, "A(01)") != NULL);
    /* control register mapping onto the lines */
    epp_control_write(&port, 0x05); /* nStrobe low */
    CHECK_EQ_INT(f.level[EPP_GPIO_NWRITE], 0);
    epp_control_write(&port, 0x0A); /* nAutoFd and nSelectIn low */
    CHECK_EQ_INT(f.level[EPP_GPIO_NWRITE], 1);
    epp_control_write(&port, 0x04);
    CHECK_EQ_INT(f.level[EPP_GPIO_NDATASTR], 1);
    CHECK_EQ_INT(f.level[EPP_GPIO_NADDRSTR], 1);
    epp_spp_data_write(&port, 0xC3);
    CHECK_EQ_INT(f.bus_out, 1);
    CHECK_EQ_INT(f.bus_host, 0xC3);
    epp_port_close(&port);

    /* incomplete line layer */
    struct epp_gpio_lines bad = l;
    bad.get = NULL;
    CHECK_EQ_INT(epp_gpiod_open(&port, &bad, 10000, "gpiod:x", err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "incomplete line layer") != NULL);
}

int main(void)
{
    RUN(test_raw_instructions);
    RUN(test_raw_narrow_and_no_ecr);
    RUN(test_raw_ioperm_failure);
    RUN(test_raw_timeout_and_clear);
    RUN(test_batching_queue);
    RUN(test_bad_arguments);
    RUN(test_open_specs);
    RUN(test_gpiod_parse);
    RUN(test_ppdev);
    RUN(test_gpiod_cycles);
    RUN(test_gpiod_timeout);
    return check_summary();
}
