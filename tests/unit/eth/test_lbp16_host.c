/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * test_lbp16_host.c - the host side of LBP16 (host/driver/backends/eth/lbp16.c)
 * against the command-word layout of spec/hostmot2.md 17.3: every space,
 * every element size, with and without address increment, the servo-cycle
 * and synchronous tails byte for byte, and the reply checks refusing short,
 * long, stale and missing replies.  A refused append leaves the packet as it
 * was.
 */
#include <errno.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "lbp16.h"

static unsigned word_at(const struct lbp16_pkt *p, size_t off)
{
    return (unsigned)p->buf[off] | (unsigned)p->buf[off + 1] << 8;
}

/* The command word the spec's bit table gives, computed field by field. */
static unsigned spec_word(int write, unsigned space, unsigned size, int inc, unsigned count)
{
    unsigned size_code = size == 1 ? 0 : size == 2 ? 1 : 2;
    return (write ? 1u << 15 : 0) | 1u << 14 | space << 10 | size_code << 8 |
           (inc ? 1u << 7 : 0) | count;
}

static void test_spec_examples(void)
{
    /* The common words spec 17.3 lists, built through the API. */
    struct lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_HM2, 4, 0x0100, 1, 0), 0);
    CHECK_EQ_INT(word_at(&p, 0), 0x4201);
    CHECK_EQ_INT(word_at(&p, 2), 0x0100);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_INFO, 2, 0, 8, 1), 0);
    CHECK_EQ_INT(word_at(&p, 4), 0x5D88);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_EEPROM, 2, 2, 3, 1), 0);
    CHECK_EQ_INT(word_at(&p, 8), 0x4983);
    CHECK_EQ_INT(word_at(&p, 10), 0x0002);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_FLASH, 4, 8, 1, 0), 0);
    CHECK_EQ_INT(word_at(&p, 12), 0x4E01);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_TIMERS, 2, 0x10, 4, 1), 0);
    CHECK_EQ_INT(word_at(&p, 16), 0x5184);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_STATUS, 2, 0x08, 1, 0), 0);
    CHECK_EQ_INT(word_at(&p, 20), 0x5901);
    CHECK_EQ_INT(p.len, 24);
    CHECK_EQ_INT(p.reply_len, 4 + 16 + 6 + 4 + 8 + 2);

    uint32_t words[5] = {1, 2, 3, 4, 5};
    lbp16_reset(&p);
    CHECK_EQ_INT(p.len, 0);
    CHECK_EQ_INT(p.reply_len, 0);
    CHECK_EQ_INT(lbp16_add_write(&p, LBP16_SPACE_HM2, 4, 0x1000, 5, 1, words), 0);
    CHECK_EQ_INT(word_at(&p, 0), 0xC285);
    CHECK_EQ_INT(p.len, 4 + 20);
    CHECK_EQ_INT(p.reply_len, 0); /* a write adds nothing to the reply */
    uint16_t one = 1;
    CHECK_EQ_INT(lbp16_add_write(&p, LBP16_SPACE_STATUS, 2, 0x1C, 1, 0, &one), 0);
    CHECK_EQ_INT(word_at(&p, 24), 0xD901);
    CHECK_EQ_INT(word_at(&p, 26), 0x001C);
    CHECK_EQ_INT(word_at(&p, 28), 1);
}

static void test_every_space_size_inc(void)
{
    static const unsigned sizes[3] = {1, 2, 4};
    for (unsigned space = 0; space < 8; space++)
        for (unsigned si = 0; si < 3; si++)
            for (int inc = 0; inc < 2; inc++)
                for (int write = 0; write < 2; write++) {
                    struct lbp16_pkt p;
                    uint8_t data[LBP16_MAX_COUNT * 4];
                    unsigned size = sizes[si];
                    unsigned count = 1 + (space * 17 + si * 5 + (unsigned)inc) % LBP16_MAX_COUNT;
                    uint16_t addr = (uint16_t)(0x0400 + space * 0x40 + si * 4);
                    for (size_t i = 0; i < sizeof data; i++)
                        data[i] = (uint8_t)(i * 7 + space);
                    lbp16_reset(&p);
                    int r = write ? lbp16_add_write(&p, space, size, addr, count, inc, data)
                                  : lbp16_add_read(&p, space, size, addr, count, inc);
                    CHECK_EQ_INT(r, 0);
                    CHECK_EQ_INT(word_at(&p, 0), spec_word(write, space, size, inc, count));
                    CHECK_EQ_INT(word_at(&p, 2), addr);
                    CHECK_EQ_INT(p.len, 4 + (write ? count * size : 0));
                    CHECK_EQ_INT(p.reply_len, write ? 0 : count * size);
                    if (write)
                        CHECK(memcmp(p.buf + 4, data, count * size) == 0);
                }
}

static void test_counts_at_limits(void)
{
    struct lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_HM2, 4, 0, 1, 1), 0);
    CHECK_EQ_INT(word_at(&p, 0) & 0x7F, 1);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_HM2, 4, 0, LBP16_MAX_COUNT, 1), 0);
    CHECK_EQ_INT(word_at(&p, 4), 0x42FF);
    CHECK_EQ_INT(p.reply_len, 4 + 127 * 4);
}

static void test_bad_arguments(void)
{
    struct lbp16_pkt p;
    uint8_t data[8] = {0};
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, LBP16_SPACE_TIMERS, 2, 0x10, 1, 1), 0);
    struct lbp16_pkt before = p; /* every refusal leaves the packet as it was */
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 0, 1), -EINVAL);        /* count 0 */
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 128, 1), -EINVAL);      /* count > 127 */
    CHECK_EQ_INT(lbp16_add_read(&p, 8, 2, 0, 1, 1), -EINVAL);        /* no space 8 */
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 8, 0, 1, 1), -EINVAL);        /* 64-bit: host never */
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 3, 0, 1, 1), -EINVAL);        /* not a size */
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 0, 0, 1, 1), -EINVAL);
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0, 1, 1, NULL), -EINVAL); /* no data */
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0, 0, 1, data), -EINVAL);
    CHECK_EQ_INT(lbp16_add_write(&p, 1, 5, 0, 1, 1, data), -EINVAL);
    CHECK_EQ_INT(p.len, before.len);
    CHECK_EQ_INT(p.reply_len, before.reply_len);
    CHECK(memcmp(p.buf, before.buf, p.len) == 0);
}

static void test_request_too_big(void)
{
    /* Writes: 127 x 4 data bytes + 4 per command; the 3rd does not fit 1472. */
    struct lbp16_pkt p;
    uint8_t data[LBP16_MAX_COUNT * 4];
    memset(data, 0xA5, sizeof data);
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0, 127, 1, data), 0);
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0, 127, 1, data), 0);
    size_t len = p.len;
    CHECK_EQ_INT(len, 2 * 512);
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0, 127, 1, data), -ENOSPC);
    CHECK_EQ_INT(p.len, len);
    /* exactly what is left still fits: 1472 - 1024 = 448 = 4 + 111 * 4 */
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0, 112, 1, data), -ENOSPC);
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0, 111, 1, data), 0);
    CHECK_EQ_INT(p.len, LBP16_MAX_PACKET);
    CHECK_EQ_INT(lbp16_add_write(&p, 1, 2, 0, 1, 0, data), -ENOSPC);
    CHECK_EQ_INT(lbp16_add_read(&p, 1, 2, 0, 1, 0), -ENOSPC); /* command bytes too */
    CHECK_EQ_INT(p.len, LBP16_MAX_PACKET);
}

static void test_reply_too_big(void)
{
    /* Reads: the request stays small, the reply may not pass 1472 bytes. */
    struct lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 127, 1), 0);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 127, 1), 0);
    CHECK_EQ_INT(p.reply_len, 1016);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 127, 1), -ENOSPC);
    CHECK_EQ_INT(p.reply_len, 1016);
    CHECK_EQ_INT(p.len, 8);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 114, 1), 0); /* 1016 + 456 = 1472 */
    CHECK_EQ_INT(p.reply_len, LBP16_MAX_PACKET);
    CHECK_EQ_INT(lbp16_add_read(&p, 1, 1, 0, 1, 0), -ENOSPC);
}

static void test_read_tail_layout(void)
{
    /* spec 17.3: 0x5901 @0x08, 0xD182 @0x10 + 4-byte counter, 0x5184 @0x10 */
    static const uint8_t want[] = {0x01, 0x59, 0x08, 0x00, 0x82, 0xD1, 0x10, 0x00,
                                   0x78, 0x56, 0x34, 0x12, 0x84, 0x51, 0x10, 0x00};
    struct lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0x3000, 3, 1), 0);
    CHECK_EQ_INT(lbp16_add_read_tail(&p, 0x12345678u), 0);
    CHECK_EQ_INT(p.len, 4 + sizeof want);
    CHECK(memcmp(p.buf + 4, want, sizeof want) == 0);
    CHECK_EQ_INT(p.reply_len, 12 + LBP16_READ_TAIL_REPLY);

    static const uint8_t wtail[] = {0x82, 0xD1, 0x14, 0x00, 0xEF, 0xBE, 0xAD, 0xDE};
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write_tail(&p, 0xDEADBEEFu), 0);
    CHECK_EQ_INT(p.len, sizeof wtail);
    CHECK(memcmp(p.buf, wtail, sizeof wtail) == 0);
    CHECK_EQ_INT(p.reply_len, 0);

    static const uint8_t stail[] = {0x82, 0xD1, 0x18, 0x00, 0x04, 0x03,
                                    0x02, 0x01, 0x82, 0x51, 0x18, 0x00};
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_sync_tag(&p, 0x01020304u), 0);
    CHECK_EQ_INT(p.len, sizeof stail);
    CHECK(memcmp(p.buf, stail, sizeof stail) == 0);
    CHECK_EQ_INT(p.reply_len, LBP16_SYNC_TAIL_REPLY);
}

static void test_tail_does_not_fit(void)
{
    /* A tail that would overflow is refused and the packet kept. */
    struct lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 127, 1), 0);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 127, 1), 0);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 112, 1), 0); /* reply 1464 */
    size_t len = p.len, rl = p.reply_len;
    /* the tail's first read (2 bytes) would fit, its last (8) would not */
    CHECK_EQ_INT(lbp16_add_read_tail(&p, 1), -ENOSPC);
    CHECK_EQ_INT(p.len, len);
    CHECK_EQ_INT(p.reply_len, rl);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0, 2, 1), 0); /* 1472: the read tail never fits */
    rl = p.reply_len;
    len = p.len;
    CHECK_EQ_INT(lbp16_add_sync_tag(&p, 1), -ENOSPC);
    CHECK_EQ_INT(p.len, len);
    CHECK_EQ_INT(p.reply_len, rl);
}

/* A reply of `n` bytes made of `data` bytes then the servo tail. */
static size_t make_read_reply(uint8_t *r, size_t data, uint16_t rx, uint32_t rseq, uint32_t wseq)
{
    for (size_t i = 0; i < data; i++)
        r[i] = (uint8_t)(0x40 + i);
    uint8_t *t = r + data;
    t[0] = (uint8_t)rx;
    t[1] = (uint8_t)(rx >> 8);
    for (int i = 0; i < 4; i++) {
        t[2 + i] = (uint8_t)(rseq >> (8 * i));
        t[6 + i] = (uint8_t)(wseq >> (8 * i));
    }
    return data + LBP16_READ_TAIL_REPLY;
}

static void test_check_read_reply(void)
{
    uint8_t r[64];
    struct lbp16_reply_check c = {0xAAAA, 0xBBBBBBBB, 0xCCCCCCCC};
    size_t n = make_read_reply(r, 12, 0x1234, 77, 76);
    CHECK_EQ_INT(lbp16_check_read_reply(r, n, n, 77, &c), 0);
    CHECK_EQ_INT(c.rx_packets, 0x1234);
    CHECK_EQ_INT(c.read_seq, 77);
    CHECK_EQ_INT(c.write_seq, 76);
    CHECK_EQ_INT(lbp16_check_read_reply(r, n, n, 77, NULL), 0);

    /* a late reply: right length, other cycle's sequence number; out untouched */
    struct lbp16_reply_check keep = {1, 2, 3};
    CHECK_EQ_INT(lbp16_check_read_reply(r, n, n, 78, &keep), -ESTALE);
    CHECK_EQ_INT(keep.rx_packets, 1);
    CHECK_EQ_INT(keep.read_seq, 2);
    CHECK_EQ_INT(keep.write_seq, 3);

    /* short, long, empty, missing: not this packet's reply */
    CHECK_EQ_INT(lbp16_check_read_reply(r, n - 1, n, 77, &keep), -EMSGSIZE);
    CHECK_EQ_INT(lbp16_check_read_reply(r, n + 1, n, 77, &keep), -EMSGSIZE);
    CHECK_EQ_INT(lbp16_check_read_reply(r, 0, n, 77, &keep), -EMSGSIZE);
    CHECK_EQ_INT(lbp16_check_read_reply(NULL, n, n, 77, &keep), -EMSGSIZE);
    /* a request without the tail cannot be checked */
    CHECK_EQ_INT(lbp16_check_read_reply(r, 9, 9, 77, &keep), -EMSGSIZE);
    CHECK_EQ_INT(keep.read_seq, 2);

    /* the tail alone (no hm2 reads) is a valid reply */
    n = make_read_reply(r, 0, 5, 0xFFFFFFFFu, 0);
    CHECK_EQ_INT(lbp16_check_read_reply(r, n, n, 0xFFFFFFFFu, &c), 0);
    CHECK_EQ_INT(c.rx_packets, 5);
}

static void test_check_sync_reply(void)
{
    uint8_t r[12] = {9, 9, 9, 9, 9, 9, 9, 9, 0x04, 0x03, 0x02, 0x01};
    CHECK_EQ_INT(lbp16_check_sync_reply(r, 12, 12, 0x01020304u), 0);
    CHECK_EQ_INT(lbp16_check_sync_reply(r, 12, 12, 0x01020305u), -ESTALE);
    CHECK_EQ_INT(lbp16_check_sync_reply(r, 11, 12, 0x01020304u), -EMSGSIZE);
    CHECK_EQ_INT(lbp16_check_sync_reply(r, 13, 12, 0x01020304u), -EMSGSIZE);
    CHECK_EQ_INT(lbp16_check_sync_reply(r, 3, 3, 0x01020304u), -EMSGSIZE);
    CHECK_EQ_INT(lbp16_check_sync_reply(NULL, 12, 12, 0x01020304u), -EMSGSIZE);
    CHECK_EQ_INT(lbp16_check_sync_reply(r + 8, 4, 4, 0x01020304u), 0);
}

int main(void)
{
    RUN(test_spec_examples);
    RUN(test_every_space_size_inc);
    RUN(test_counts_at_limits);
    RUN(test_bad_arguments);
    RUN(test_request_too_big);
    RUN(test_reply_too_big);
    RUN(test_read_tail_layout);
    RUN(test_tail_does_not_fit);
    RUN(test_check_read_reply);
    RUN(test_check_sync_reply);
    return check_summary();
}
