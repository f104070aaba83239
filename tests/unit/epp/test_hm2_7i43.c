/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of the hm2_7i43 llio (host/driver/backends/7i43) against a model of
 * the 7i43 (tests/unit/epp/fakes.c: CPLD while blank, hm2 EPP bridge when
 * configured; spec/hostmot2.md §17.2, §18): port setup, CPLD reset and size
 * detection, bit-reversed programming, register transfers, EPP timeouts
 * with LinuxCNC's messages, queued transfers in one flush.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "../check.h"
#include "fakes.h"
#include "hm2/bitfile.h"
#include "hm2_7i43_llio.h"

static char logbuf[8192];
static size_t loglen;
static void cap_log(int level, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (loglen < sizeof(logbuf) - 256) {
        loglen += (size_t)snprintf(logbuf + loglen, sizeof(logbuf) - loglen, "%d:", level);
        loglen += (size_t)vsnprintf(logbuf + loglen, sizeof(logbuf) - loglen, fmt, ap);
    }
    va_end(ap);
}
static void log_clear(void)
{
    loglen = 0;
    logbuf[0] = 0;
}
static long long fake_time;
static long long fake_now(void)
{
    return fake_time += 1000000; /* 1 ms per call */
}

static struct periph P;
static struct pcport PC;
static struct fake_raw FR;
static epp_port_t PORT;
static struct hm2_7i43 B;

static void clear_traces(void)
{
    PC.log_len = 0;
    PC.log[0] = 0;
    P.trace_len = 0;
    P.trace[0] = 0;
}

static int setup_raw(int wide, int size400)
{
    char err[200];
    periph_init(&P, PERIPH_7I43);
    P.size400 = size400;
    pcport_init(&PC, &P);
    memset(&FR, 0, sizeof(FR));
    FR.pc = &PC;
    FR.base = 0x378;
    FR.base_hi = 0x778;
    struct epp_raw_io io = fake_raw_io(&FR);
    CHECK_EQ_INT(epp_raw_open(&PORT, &io, 0x378, 0x778, wide, err, sizeof(err)), 0);
    log_clear();
    return hm2_7i43_setup_board(&B, &PORT, 0, wide, 0, cap_log, fake_now);
}

static void test_setup(void)
{
    CHECK_EQ_INT(setup_raw(1, 1), 0);
    CHECK_EQ_STR(PC.log, "outb(94,+1026) outb(04,+2) inb(+1) inb(+1) "
                         "outb(7f,+3) outb(7f,+3) outb(5a,+4) outb(7f,+3) outb(7f,+3) "
                         "outb(5a,+4) outb(01,+3) outb(00,+4) outb(01,+4) inb(+4) "
                         "outb(00,+3) inb(+4) ");
    CHECK_EQ_STR(B.llio.fpga_part_number, "3s400tq144");
    CHECK_EQ_STR(B.llio.name, "hm2_7i43.0");
    CHECK_EQ_INT(B.llio.num_ioport_connectors, 2);
    CHECK_EQ_STR(B.llio.ioport_connector_name[0], "P4");
    CHECK_EQ_STR(B.llio.ioport_connector_name[1], "P3");
    CHECK_EQ_INT(B.llio.pins_per_connector, 24);
    CHECK_EQ_INT(B.llio.num_leds, 8);
    CHECK_EQ_INT(B.llio.threadsafe, 0);
    CHECK(B.llio.queue_read && B.llio.send_queued_reads && B.llio.queue_write &&
          B.llio.send_queued_writes && B.llio.reset && B.llio.program_fpga);
    char err[128];
    CHECK_EQ_INT(hm2_llio_validate(&B.llio, err, sizeof(err)), 0);
    CHECK_EQ_STR(logbuf, "4:hm2_7i43.0: detected FPGA '3s400tq144'\n");
    epp_port_close(&PORT);
    CHECK_EQ_INT(setup_raw(0, 0), 0);
    CHECK_EQ_STR(B.llio.fpga_part_number, "3s200tq144");
    epp_port_close(&PORT);
}

static void test_reset_done_high(void)
{
    char err[200];
    periph_init(&P, PERIPH_7I43);
    P.force_done = 1;
    pcport_init(&PC, &P);
    memset(&FR, 0, sizeof(FR));
    FR.pc = &PC;
    FR.base = 0x378;
    struct epp_raw_io io = fake_raw_io(&FR);
    CHECK_EQ_INT(epp_raw_open(&PORT, &io, 0x378, -1, 1, err, sizeof(err)), 0);
    log_clear();
    CHECK_EQ_INT(hm2_7i43_setup_board(&B, &PORT, 2, 1, 0, cap_log, fake_now), -EIO);
    CHECK_EQ_STR(logbuf, "0:hm2_7i43: /DONE is not low after CPLD reset!\n");
    CHECK_EQ_INT(PC.ecr_writes, 0); /* no ECR: none written */
    epp_port_close(&PORT);
}

static uint8_t bits[3000];

static void program(int wide, uint32_t cookie, int corrupt)
{
    static uint8_t copy[sizeof(bits)];
    CHECK_EQ_INT(setup_raw(wide, 1), 0);
    for (size_t i = 0; i < sizeof(bits); i++)
        bits[i] = (uint8_t)(i * 37 + 11);
    P.expect_bits = bits; /* what the (modelled) FPGA accepts */
    P.expect_len = sizeof(bits);
    periph_hm2_set(&P, 0x100, cookie);
    memcpy(copy, bits, sizeof(bits));
    if (corrupt)
        copy[100] ^= 0x10;
    struct hm2_bitfile bf = {"x", "3s400tq144", "d", "t", copy, sizeof(copy)};
    log_clear();
    CHECK_EQ_INT(B.llio.reset(&B.llio), 0);
    clear_traces();
    CHECK_EQ_INT(B.llio.program_fpga(&B.llio, &bf), 0);
}

static void test_program(void)
{
    program(1, 0x55AACAFE, 0);
    CHECK_EQ_INT(P.configured, 1);
    CHECK_EQ_INT(P.cfg_count, sizeof(bits));
    /* address 0, then one byte-wide data cycle per byte (never wide) */
    CHECK(strncmp(PC.log, "outb(00,+3) outb(", 17) == 0);
    CHECK(strstr(PC.log, "outl(") == NULL || strstr(PC.log, "outl(") > strstr(PC.log, "inb(+1)"));
    CHECK(strstr(logbuf, "3:hm2_7i43.0: 3000 bytes of firmware sent (") != NULL);
    CHECK(strstr(logbuf, "Falling back") == NULL);
    CHECK_EQ_INT(PORT.wide, 1);
    epp_port_close(&PORT);
    /* wrong cookie in wide mode: fall back to byte transfers */
    program(1, 0x12345678, 0);
    CHECK(strstr(logbuf, "0:hm2_7i43.0: Reading cookie with epp_wide failed. (read 0x12345678) "
                         "Falling back to byte transfers\n") != NULL);
    CHECK(strstr(logbuf, "0:hm2_7i43.0: Reading cookie still failed without epp_wide. (read "
                         "0x12345678)\n") != NULL);
    CHECK_EQ_INT(PORT.wide, 0);
    CHECK_EQ_INT(B.epp_wide, 0);
    epp_port_close(&PORT);
    /* a port whose 32-bit EPP reads are broken: bytes work */
    CHECK_EQ_INT(setup_raw(1, 1), 0);
    for (size_t i = 0; i < sizeof(bits); i++)
        bits[i] = (uint8_t)(i * 37 + 11);
    P.expect_bits = bits;
    P.expect_len = sizeof(bits);
    periph_hm2_set(&P, 0x100, 0x55AACAFE);
    FR.wide_broken = 1;
    log_clear();
    struct hm2_bitfile good = {"x", "3s400tq144", "d", "t", bits, sizeof(bits)};
    CHECK_EQ_INT(B.llio.program_fpga(&B.llio, &good), 0);
    CHECK(strstr(logbuf, "Reading cookie with epp_wide failed. (read 0xffffffff) Falling back "
                         "to byte transfers\n0:hm2_7i43.0: Successfully read cookie after "
                         "selecting byte transfers\n") != NULL);
    CHECK_EQ_INT(PORT.wide, 0);
    uint32_t c = 0;
    CHECK_EQ_INT(B.llio.read(&B.llio, 0x100, &c, 4), 0);
    CHECK_EQ_INT(c, 0x55AACAFE);
    epp_port_close(&PORT);
    /* corrupt bitstream: the board stays blank (DONE low) */
    program(0, 0x55AACAFE, 1);
    CHECK_EQ_INT(P.configured, 0);
    CHECK_EQ_INT(P.cfg_bad, 1);
    epp_port_close(&PORT);
    /* a board that stops answering while the bytes go out */
    program(0, 0x55AACAFE, 0);
    CHECK_EQ_INT(B.llio.reset(&B.llio), 0);
    P.stall = 1;
    log_clear();
    struct hm2_bitfile bf = {"x", "3s400tq144", "d", "t", bits, sizeof(bits)};
    CHECK_EQ_INT(B.llio.program_fpga(&B.llio, &bf), -EIO);
    CHECK_EQ_STR(logbuf, "0:hm2_7i43.0: EPP Timeout while sending firmware!\n");
    CHECK_EQ_INT(PC.timeout, 0);
    epp_port_close(&PORT);
}

static void test_transfers(void)
{
    program(1, 0x55AACAFE, 0);
    for (uint32_t a = 0; a < 16; a += 4)
        periph_hm2_set(&P, 0x1000 + a, 0x01020304u * (a + 1));
    uint32_t buf[4] = {0};
    clear_traces();
    CHECK_EQ_INT(B.llio.read(&B.llio, 0x1000, buf, 8), 0);
    CHECK_EQ_STR(PC.log, "outb(00,+3) outb(90,+3) inl(+4) inl(+4) inb(+1) ");
    CHECK_EQ_INT(buf[0], 0x01020304u);
    CHECK_EQ_INT(buf[1], 0x01020304u * 5);
    uint32_t w[2] = {0xDEADBEEF, 0x0BADF00D};
    clear_traces();
    CHECK_EQ_INT(B.llio.write(&B.llio, 0x2004, w, 8), 0);
    CHECK_EQ_STR(PC.log, "outb(04,+3) outb(a0,+3) outl(deadbeef,+4) outl(0badf00d,+4) inb(+1) ");
    CHECK_EQ_INT(periph_hm2_get(&P, 0x2004), 0xDEADBEEF);
    CHECK_EQ_INT(periph_hm2_get(&P, 0x2008), 0x0BADF00D);
    /* timeout: LinuxCNC's message, cleared, -EIO */
    P.stall = 1;
    log_clear();
    CHECK_EQ_INT(B.llio.read(&B.llio, 0x1000, buf, 8), -EIO);
    CHECK_EQ_STR(logbuf, "1:hm2_7i43.0: EPP timeout on data cycle of read(addr=0x1000, size=8)\n");
    CHECK_EQ_INT(PC.timeout, 0);
    log_clear();
    CHECK_EQ_INT(B.llio.write(&B.llio, 0x0C00, w, 4), -EIO);
    CHECK_EQ_STR(logbuf,
                 "1:hm2_7i43.0: EPP timeout on data cycle of write(addr=0x0c00, size=4)\n");
    P.stall = 0;
    /* bad arguments */
    log_clear();
    CHECK_EQ_INT(B.llio.read(&B.llio, 0x10000, buf, 4), -EINVAL);
    CHECK_EQ_INT(B.llio.read(&B.llio, 0, buf, 0), -EINVAL);
    CHECK(strstr(logbuf, "bad read(addr=0x10000, size=4)") != NULL);
    /* reset of a configured board: 0x5A at 0x7F7F reconfigures it */
    CHECK_EQ_INT(B.llio.reset(&B.llio), 0);
    CHECK_EQ_INT(P.reconfigs, 1);
    CHECK_EQ_INT(P.configured, 0);
    epp_port_close(&PORT);
}

static void test_debug_epp(void)
{
    program(0, 0x55AACAFE, 0);
    B.debug_epp = 1;
    uint32_t v = 0;
    log_clear();
    CHECK_EQ_INT(B.llio.read(&B.llio, 0x100, &v, 4), 0);
    CHECK_EQ_STR(logbuf, "0:hm2_7i43: selected address 0x8100\n0:hm2_7i43: read data 0x55AACAFE\n");
    epp_port_close(&PORT);
}

static void test_queued(void)
{
    char err[200];
    periph_init(&P, PERIPH_7I43);
    P.size400 = 1;
    pcport_init(&PC, &P);
    fake_batch_open(&PORT, &PC, 1);
    CHECK_EQ_INT(hm2_7i43_setup_board(&B, &PORT, 1, 1, 0, cap_log, fake_now), 0);
    (void)err;
    CHECK_EQ_STR(B.llio.name, "hm2_7i43.1");
    P.configured = 1; /* as if programmed */
    for (uint32_t a = 0; a < 64; a += 4)
        periph_hm2_set(&P, 0x3000 + a, 0xA0000000u + a);
    uint32_t r1[2], r2[1], r3[4];
    fake_batch_executes = 0;
    CHECK_EQ_INT(B.llio.queue_read(&B.llio, 0x3000, r1, 8), 0);
    CHECK_EQ_INT(B.llio.queue_read(&B.llio, 0x3010, r2, 4), 0);
    CHECK_EQ_INT(B.llio.queue_read(&B.llio, 0x3020, r3, 16), 0);
    CHECK_EQ_INT(fake_batch_executes, 0);
    CHECK_EQ_INT(B.llio.send_queued_reads(&B.llio), 0);
    CHECK_EQ_INT(fake_batch_executes, 1);
    CHECK_EQ_INT(r1[1], 0xA0000004u);
    CHECK_EQ_INT(r2[0], 0xA0000010u);
    CHECK_EQ_INT(r3[3], 0xA000002Cu);
    uint32_t w[2] = {7, 8};
    CHECK_EQ_INT(B.llio.queue_write(&B.llio, 0x4000, w, 8), 0);
    w[0] = 99; /* copied at queue time */
    CHECK_EQ_INT(B.llio.queue_write(&B.llio, 0x4100, w, 4), 0);
    CHECK_EQ_INT(B.llio.send_queued_writes(&B.llio), 0);
    CHECK_EQ_INT(fake_batch_executes, 2);
    CHECK_EQ_INT(periph_hm2_get(&P, 0x4000), 7);
    CHECK_EQ_INT(periph_hm2_get(&P, 0x4100), 99);
    /* a timeout in the batch: the first failing transfer is named */
    P.stall = 1;
    log_clear();
    B.llio.queue_read(&B.llio, 0x3000, r1, 8);
    B.llio.queue_read(&B.llio, 0x3010, r2, 4);
    CHECK_EQ_INT(B.llio.send_queued_reads(&B.llio), -EIO);
    CHECK_EQ_STR(logbuf, "1:hm2_7i43.1: EPP timeout on data cycle of read(addr=0x3000, size=8)\n");
    P.stall = 0;
    /* queue overflow discards the queue */
    log_clear();
    int r = 0;
    for (int i = 0; i <= HM2_7I43_MAX_QUEUE && !r; i++)
        r = B.llio.queue_read(&B.llio, 0x3000, r2, 4);
    CHECK_EQ_INT(r, -ENOSPC);
    CHECK(strstr(logbuf, "read queue full") != NULL);
    CHECK_EQ_INT(PORT.n_ops, 0);
    CHECK_EQ_INT(B.llio.send_queued_reads(&B.llio), 0);
    epp_port_close(&PORT);
}

int main(void)
{
    RUN(test_setup);
    RUN(test_reset_done_high);
    RUN(test_program);
    RUN(test_transfers);
    RUN(test_debug_epp);
    RUN(test_queued);
    return check_summary();
}
