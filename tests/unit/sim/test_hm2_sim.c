/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of vbclient and the hm2_sim llio against fake_board: framing,
 * one round trip per queued flush, host time carried, board-side errors
 * (reported, connection kept), transport failures (reported once, then
 * fail fast), timeouts, identity checks, FPGA configuration.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "fake_board.h"
#include "hm2/bitfile.h"
#include "hm2_sim_llio.h"
#include "vboard_client.h"

struct logbuf {
    int lines, errors;
    char last[512];
};

static void capture(void *ctx, int level, const char *line)
{
    struct logbuf *l = ctx;
    l->lines++;
    if (level == HM2_ERR)
        l->errors++;
    snprintf(l->last, sizeof(l->last), "%s", line);
}

static int64_t fixed_time(void)
{
    return 123456789;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* the first request on a fresh connection has no payload (HELLO): this
 * used to write the header through a NULL buffer */
static void test_hello_first(void)
{
    struct fake_board fb;
    CHECK(fake_board_start(&fb, "5i20", VB_BUS_LOCAL, VB_STATE_CONFIGURED) == 0);
    vbc_t c;
    CHECK_EQ_INT(vbc_open(&c, fb.path), 0);
    struct vb_hello h;
    CHECK_EQ_INT(vbc_hello(&c, &h), 0);
    CHECK_EQ_STR(h.board, "5i20");
    CHECK_EQ_INT(h.bus, VB_BUS_LOCAL);
    CHECK_EQ_INT(c.seq, 1);
    vbc_close(&c);
    fake_board_stop(&fb);
}

static void test_connect_errors(void)
{
    vbc_t c;
    CHECK_EQ_INT(vbc_open(&c, "/tmp/no-such-board-socket.sock"), -ENODEV);
    CHECK(strstr(c.err, "cannot connect") != NULL);
    vbc_close(&c);
    char longpath[200];
    memset(longpath, 'x', sizeof(longpath) - 1);
    longpath[sizeof(longpath) - 1] = 0;
    CHECK_EQ_INT(vbc_open(&c, longpath), -EINVAL);
    CHECK(strstr(c.err, "too long") != NULL);
    vbc_close(&c);
    /* calls on a closed client fail at once */
    CHECK_EQ_INT(vbc_call(&c, VB_HELLO, 0, NULL, 0), -ENODEV);
    vbc_close(&c);
}

static int setup(struct fake_board *fb, struct hm2_sim_board *sb, struct logbuf *log)
{
    memset(log, 0, sizeof(*log));
    if (fake_board_start(fb, "5i20", VB_BUS_LOCAL, VB_STATE_CONFIGURED))
        return -1;
    return hm2_sim_setup(sb, fb->path, "5i20", 1, fixed_time, capture, log);
}

static void test_llio_identity(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log;
    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    CHECK_EQ_STR(sb.llio.name, "hm2_5i20.1");
    CHECK_EQ_INT(sb.llio.num_ioport_connectors, 3);
    CHECK_EQ_INT(sb.llio.pins_per_connector, 24);
    CHECK_EQ_STR(sb.llio.fpga_part_number, "2s200pq208");
    CHECK(sb.llio.program_fpga != NULL && sb.llio.reset != NULL);
    char err[128];
    CHECK_EQ_INT(hm2_llio_validate(&sb.llio, err, sizeof(err)), 0);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
}

static void test_read_write(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log;
    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    hm2_llio_t *l = &sb.llio;
    uint32_t w[3] = {0x11223344, 0xdeadbeef, 7}, r[3] = {0};
    CHECK_EQ_INT(l->write(l, 0x1000, w, sizeof(w)), 0);
    CHECK_EQ_INT(fb.last_time_ns, 123456789);
    CHECK_EQ_INT(l->read(l, 0x1000, r, sizeof(r)), 0);
    CHECK(memcmp(w, r, sizeof(w)) == 0);
    /* bad arguments are refused locally, no request */
    int before = fb.requests;
    CHECK_EQ_INT(l->read(l, 0x1002, r, 4), -EINVAL);
    CHECK_EQ_INT(l->write(l, 0x1000, w, 6), -EINVAL);
    CHECK_EQ_INT(l->read(l, 0x1000, r, 0), -EINVAL);
    CHECK_EQ_INT(fb.requests, before);
    CHECK(strstr(log.last, "multiples of 4") != NULL);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
}

static void test_queued_one_round_trip(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log;
    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    hm2_llio_t *l = &sb.llio;
    /* 100 queued writes of different sizes: one WRITE request */
    int before = fb.requests;
    for (uint32_t i = 0; i < 100; i++) {
        uint32_t v[2] = {i, ~i};
        CHECK_EQ_INT(l->queue_write(l, 0x2000 + i * 8, v, (i % 2) ? 8 : 4), 0);
    }
    CHECK_EQ_INT(fb.requests, before);
    CHECK_EQ_INT(l->send_queued_writes(l), 0);
    CHECK_EQ_INT(fb.requests, before + 1);
    CHECK_EQ_INT(fb.last_xfers, 100);
    /* 100 queued reads land in their own buffers: one READ request */
    uint32_t got[100][2];
    memset(got, 0xA5, sizeof(got));
    for (uint32_t i = 0; i < 100; i++)
        CHECK_EQ_INT(l->queue_read(l, 0x2000 + i * 8, got[i], (i % 2) ? 8 : 4), 0);
    CHECK_EQ_INT(l->send_queued_reads(l), 0);
    CHECK_EQ_INT(fb.requests, before + 2);
    CHECK_EQ_INT(fb.last_xfers, 100);
    for (uint32_t i = 0; i < 100; i++) {
        CHECK_EQ_INT(got[i][0], i);
        CHECK_EQ_INT(got[i][1], (i % 2) ? ~i : 0xA5A5A5A5u);
    }
    /* empty flushes cost nothing */
    CHECK_EQ_INT(l->send_queued_reads(l), 0);
    CHECK_EQ_INT(l->send_queued_writes(l), 0);
    CHECK_EQ_INT(fb.requests, before + 2);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
}

static void test_board_error_keeps_connection(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log;
    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    hm2_llio_t *l = &sb.llio;
    uint32_t r[2];
    /* 0xFFFC + 8 bytes runs past the window: the board refuses it */
    CHECK_EQ_INT(l->read(l, 0xFFFC, r, 8), -EINVAL);
    CHECK(strstr(log.last, "outside the register window") != NULL);
    CHECK(strstr(log.last, "hm2_5i20.1") != NULL);
    CHECK_EQ_INT(sb.dead, 0);
    CHECK_EQ_INT(l->read(l, 0x0100, r, 4), 0);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
}

static void test_board_gone_reported_once(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log;
    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    hm2_llio_t *l = &sb.llio;
    fb.fault = FAKE_CLOSE;
    fb.fault_at = fb.requests + 1;
    uint32_t r = 0;
    CHECK_EQ_INT(l->queue_read(l, 0x100, &r, 4), 0);
    CHECK_EQ_INT(l->send_queued_reads(l), -ENODEV);
    CHECK_EQ_INT(log.errors, 1);
    CHECK(strstr(log.last, "the board is gone") != NULL);
    int req = fb.requests;
    for (int i = 0; i < 1000; i++) {
        CHECK_EQ_INT(l->queue_read(l, 0x100, &r, 4), 0);
        CHECK_EQ_INT(l->send_queued_reads(l), -ENODEV);
        CHECK_EQ_INT(l->queue_write(l, 0x100, &r, 4), 0);
        CHECK_EQ_INT(l->send_queued_writes(l), -ENODEV);
        CHECK_EQ_INT(l->read(l, 0x100, &r, 4), -ENODEV);
    }
    CHECK_EQ_INT(log.errors, 1); /* no report per call */
    CHECK_EQ_INT(fb.requests, req);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
}

static void test_timeout_and_bad_reply(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log;
    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    hm2_llio_t *l = &sb.llio;
    sb.vbc.timeout_ms = 200;
    fb.fault = FAKE_SILENT;
    fb.fault_at = fb.requests + 1;
    uint32_t r = 0;
    double t0 = now_s();
    CHECK_EQ_INT(l->read(l, 0x100, &r, 4), -ENODEV);
    double dt = now_s() - t0;
    /* behaviour, not speed: it waits the whole timeout, then gives up
     * (the upper bound only catches a hang, loose for loaded CI machines) */
    CHECK(dt >= 0.19 && dt < 30.0);
    CHECK(strstr(log.last, "no reply within the timeout") != NULL);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);

    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    fb.fault = FAKE_BAD_SEQ;
    fb.fault_at = fb.requests + 1;
    CHECK_EQ_INT(sb.llio.write(&sb.llio, 0x100, &r, 4), -ENODEV);
    CHECK(strstr(log.last, "does not match the request") != NULL);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
}

/* a board that stops reading: a big request cannot block the caller past
 * the timeout */
static void test_send_timeout(void)
{
    struct fake_board fb;
    CHECK(fake_board_start(&fb, "5i20", VB_BUS_LOCAL, VB_STATE_CONFIGURED) == 0);
    vbc_t c;
    CHECK_EQ_INT(vbc_open(&c, fb.path), 0);
    c.timeout_ms = 200;
    fb.fault = FAKE_STALL;
    fb.fault_at = 1;
    size_t n = 8u << 20;
    uint8_t *big = calloc(1, n);
    CHECK(big != NULL);
    vbc_req_start(&c);
    CHECK_EQ_INT(vbc_req_put(&c, big, n), 0);
    double t0 = now_s();
    CHECK_EQ_INT(vbc_send(&c, VB_CONFIG, 0), -ETIMEDOUT);
    double dt = now_s() - t0;
    CHECK(dt >= 0.19 && dt < 30.0); /* waits the timeout, does not hang */
    CHECK(strstr(c.err, "send timeout") != NULL);
    CHECK_EQ_INT(c.fd, -1);
    free(big);
    vbc_close(&c);
    fb.stall_release = 1;
    fake_board_stop(&fb);
}

static void test_identity_checks(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log = {0};
    CHECK(fake_board_start(&fb, "7i43", VB_BUS_EPP_HM2, VB_STATE_CONFIGURED) == 0);
    CHECK_EQ_INT(hm2_sim_setup(&sb, fb.path, NULL, 0, NULL, capture, &log), -ENODEV);
    CHECK(strstr(log.last, "not a local-bus") != NULL);
    fake_board_stop(&fb);
    CHECK(fake_board_start(&fb, "5i20", VB_BUS_LOCAL, VB_STATE_BLANK) == 0);
    CHECK_EQ_INT(hm2_sim_setup(&sb, fb.path, "5i25", 0, NULL, capture, &log), -ENODEV);
    CHECK(strstr(log.last, "is a 5i20, but board=5i25") != NULL);
    /* no board= given: the board's own name is used */
    CHECK_EQ_INT(hm2_sim_setup(&sb, fb.path, "", 0, NULL, capture, &log), 0);
    CHECK_EQ_STR(sb.llio.name, "hm2_5i20.0");
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
    CHECK(fake_board_start(&fb, "9x99", VB_BUS_LOCAL, VB_STATE_BLANK) == 0);
    CHECK_EQ_INT(hm2_sim_setup(&sb, fb.path, NULL, 0, NULL, capture, &log), -ENODEV);
    CHECK(strstr(log.last, "not in the board table") != NULL);
    fake_board_stop(&fb);
    CHECK_EQ_INT(hm2_sim_setup(&sb, "/tmp/no-such-board.sock", NULL, 0, NULL, capture, &log),
                 -ENODEV);
    CHECK(strstr(log.last, "is bin/vboard running?") != NULL);
}

static void test_configuration(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log;
    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    hm2_llio_t *l = &sb.llio;
    CHECK_EQ_INT(l->reset(l), 0);
    CHECK_EQ_INT(fb.state, VB_STATE_BLANK);
    struct hm2_bitfile bad = {"d", "2s200pq208", "", "", (const uint8_t *)"JUNKJUNK", 8};
    CHECK_EQ_INT(l->program_fpga(l, &bad), -EIO);
    CHECK(strstr(log.last, "refused the 8-byte bitstream") != NULL);
    CHECK(strstr(log.last, "image is not for this board") != NULL);
    CHECK_EQ_INT(fb.state, VB_STATE_BLANK);
    CHECK_EQ_INT(sb.dead, 0);
    struct hm2_bitfile good = {"d", "2s200pq208", "", "", (const uint8_t *)"GOOD....", 8};
    CHECK_EQ_INT(l->program_fpga(l, &good), 0);
    CHECK_EQ_INT(fb.state, VB_STATE_CONFIGURED);
    CHECK_EQ_STR(sb.hello.firmware, "FAKEFW");
    /* the board goes away: configuration fails with ENODEV */
    fb.fault = FAKE_CLOSE;
    fb.fault_at = fb.requests + 1;
    CHECK_EQ_INT(l->reset(l), -ENODEV);
    CHECK_EQ_INT(l->program_fpga(l, &good), -ENODEV);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
}

/* writes sent without waiting: in order with later requests, their board
 * errors reported by the next request, one round trip per period */
static void test_async_writes(void)
{
    struct fake_board fb;
    struct hm2_sim_board sb;
    struct logbuf log;
    CHECK_EQ_INT(setup(&fb, &sb, &log), 0);
    hm2_llio_t *l = &sb.llio;
    sb.async_writes = 1;
    uint32_t v = 0xCAFEF00D, r = 0;
    CHECK_EQ_INT(l->queue_write(l, 0x3000, &v, 4), 0);
    CHECK_EQ_INT(l->send_queued_writes(l), 0);
    CHECK_EQ_INT(sb.vbc.posted, 1);
    CHECK_EQ_INT(l->queue_read(l, 0x3000, &r, 4), 0);
    CHECK_EQ_INT(l->send_queued_reads(l), 0);
    CHECK_EQ_INT(r, 0xCAFEF00D);
    CHECK_EQ_INT(sb.vbc.posted, 0);
    /* a posted write the board refuses: the next request reports it */
    uint32_t two[2] = {1, 2};
    int req = fb.requests; /* before the post: the board may serve it at once */
    CHECK_EQ_INT(l->queue_write(l, 0xFFFC, two, 8), 0);
    CHECK_EQ_INT(l->send_queued_writes(l), 0);
    CHECK_EQ_INT(l->read(l, 0x3000, &r, 4), -EINVAL);
    CHECK(strstr(log.last, "outside the register window") != NULL);
    CHECK(strstr(log.last, "reply to an earlier request") != NULL);
    CHECK_EQ_INT(fb.requests, req + 1); /* only the write reached the board */
    CHECK_EQ_INT(l->read(l, 0x3000, &r, 4), 0);
    /* the board dies with a write outstanding: the next call says so */
    CHECK_EQ_INT(l->queue_write(l, 0x3000, &v, 4), 0);
    fb.fault = FAKE_CLOSE;
    fb.fault_at = fb.requests + 1;
    CHECK_EQ_INT(l->send_queued_writes(l), 0);
    CHECK_EQ_INT(l->read(l, 0x3000, &r, 4), -ENODEV);
    CHECK(strstr(log.last, "the board is gone") != NULL);
    hm2_sim_teardown(&sb);
    fake_board_stop(&fb);
}

int main(void)
{
    RUN(test_hello_first);
    RUN(test_connect_errors);
    RUN(test_llio_identity);
    RUN(test_read_write);
    RUN(test_queued_one_round_trip);
    RUN(test_board_error_keeps_connection);
    RUN(test_board_gone_reported_once);
    RUN(test_timeout_and_bad_reply);
    RUN(test_send_timeout);
    RUN(test_identity_checks);
    RUN(test_configuration);
    RUN(test_async_writes);
    return check_summary();
}
