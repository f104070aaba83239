/* SPDX-License-Identifier: GPL-2.0-or-later */
/* lbp16.c - LBP16 request building and reply checks (lbp16.h). */
#include "lbp16.h"

#include <errno.h>
#include <string.h>

static void put16(uint8_t *p, unsigned v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static unsigned size_bits(unsigned size)
{
    switch (size) {
    case 1: return LBP16_SIZE8;
    case 2: return LBP16_SIZE16;
    case 4: return LBP16_SIZE32;
    default: return 0xFFFFu;
    }
}

void lbp16_reset(struct lbp16_pkt *p)
{
    p->len = 0;
    p->reply_len = 0;
}

static int add(struct lbp16_pkt *p, unsigned cmd, unsigned space, unsigned size, uint16_t addr,
               unsigned count, int inc, const void *data)
{
    unsigned sb = size_bits(size);
    if (sb == 0xFFFFu || count == 0 || count > LBP16_MAX_COUNT || space > 7)
        return -EINVAL;
    size_t dlen = (size_t)count * size;
    size_t need = 4 + (data ? dlen : 0);
    if (p->len + need > sizeof(p->buf) || (!data && p->reply_len + dlen > LBP16_MAX_PACKET))
        return -ENOSPC;
    put16(p->buf + p->len,
          cmd | LBP16_ADDR | LBP16_SPACE(space) | sb | (inc ? LBP16_INC : 0) | count);
    put16(p->buf + p->len + 2, addr);
    p->len += 4;
    if (data) {
        memcpy(p->buf + p->len, data, dlen);
        p->len += dlen;
    } else {
        p->reply_len += dlen;
    }
    return 0;
}

int lbp16_add_read(struct lbp16_pkt *p, unsigned space, unsigned size, uint16_t addr,
                   unsigned count, int inc)
{
    return add(p, 0, space, size, addr, count, inc, NULL);
}

int lbp16_add_write(struct lbp16_pkt *p, unsigned space, unsigned size, uint16_t addr,
                    unsigned count, int inc, const void *data)
{
    if (!data)
        return -EINVAL;
    return add(p, LBP16_WRITE, space, size, addr, count, inc, data);
}

int lbp16_add_read_tail(struct lbp16_pkt *p, uint32_t read_seq)
{
    uint8_t seq[4] = {(uint8_t)read_seq, (uint8_t)(read_seq >> 8), (uint8_t)(read_seq >> 16),
                      (uint8_t)(read_seq >> 24)};
    size_t len = p->len, reply_len = p->reply_len;
    int r;
    if ((r = lbp16_add_read(p, LBP16_SPACE_STATUS, 2, LBP16_STATUS_RX_PACKETS, 1, 0)) ||
        (r = lbp16_add_write(p, LBP16_SPACE_TIMERS, 2, LBP16_SCRATCH_READ_SEQ, 2, 1, seq)) ||
        (r = lbp16_add_read(p, LBP16_SPACE_TIMERS, 2, LBP16_SCRATCH_READ_SEQ, 4, 1)))
        goto undo;
    return 0;
undo: /* all of the tail or none of it */
    p->len = len;
    p->reply_len = reply_len;
    return r;
}

int lbp16_add_write_tail(struct lbp16_pkt *p, uint32_t write_seq)
{
    uint8_t seq[4] = {(uint8_t)write_seq, (uint8_t)(write_seq >> 8), (uint8_t)(write_seq >> 16),
                      (uint8_t)(write_seq >> 24)};
    return lbp16_add_write(p, LBP16_SPACE_TIMERS, 2, LBP16_SCRATCH_WRITE_SEQ, 2, 1, seq);
}

int lbp16_check_read_reply(const uint8_t *r, size_t n, size_t reply_len, uint32_t read_seq,
                           struct lbp16_reply_check *out)
{
    if (!r || reply_len < LBP16_READ_TAIL_REPLY || n != reply_len)
        return -EMSGSIZE;
    const uint8_t *t = r + reply_len - LBP16_READ_TAIL_REPLY;
    struct lbp16_reply_check c;
    c.rx_packets = (uint16_t)(t[0] | t[1] << 8);
    c.read_seq = get32(t + 2);
    c.write_seq = get32(t + 6);
    if (c.read_seq != read_seq)
        return -ESTALE;
    if (out)
        *out = c;
    return 0;
}

int lbp16_add_sync_tag(struct lbp16_pkt *p, uint32_t tag)
{
    uint8_t t[4] = {(uint8_t)tag, (uint8_t)(tag >> 8), (uint8_t)(tag >> 16), (uint8_t)(tag >> 24)};
    size_t len = p->len, reply_len = p->reply_len;
    int r;
    if ((r = lbp16_add_write(p, LBP16_SPACE_TIMERS, 2, LBP16_SCRATCH_SYNC_TAG, 2, 1, t)) ||
        (r = lbp16_add_read(p, LBP16_SPACE_TIMERS, 2, LBP16_SCRATCH_SYNC_TAG, 2, 1)))
        goto undo;
    return 0;
undo: /* all of the tag or none of it */
    p->len = len;
    p->reply_len = reply_len;
    return r;
}

int lbp16_check_sync_reply(const uint8_t *r, size_t n, size_t reply_len, uint32_t tag)
{
    if (!r || reply_len < LBP16_SYNC_TAIL_REPLY || n != reply_len)
        return -EMSGSIZE;
    return get32(r + reply_len - LBP16_SYNC_TAIL_REPLY) == tag ? 0 : -ESTALE;
}
