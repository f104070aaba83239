/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * libFuzzer target: hm2_eth's LBP16 reply checks and request builder
 * (host/driver/backends/eth/lbp16.c).  Any reply of any length against any
 * expected length/sequence number is accepted only when it has exactly the
 * expected length and echoes the sequence number or tag; building requests
 * from arbitrary arguments never writes past the packet buffer and the
 * lengths it reports match what was appended.
 */
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "lbp16.h"

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 8)
        return 0;
    size_t reply_len = (size_t)(data[0] | data[1] << 8);
    uint32_t seq = le32(data + 2);
    const uint8_t *r = data + 8;
    size_t n = size - 8;
    struct lbp16_reply_check c;
    int rc = lbp16_check_read_reply(r, n, reply_len, seq, &c);
    if (rc == 0 && (n != reply_len || n < LBP16_READ_TAIL_REPLY || c.read_seq != seq))
        abort();
    if (rc != 0 && rc != -EMSGSIZE && rc != -ESTALE)
        abort();
    rc = lbp16_check_sync_reply(r, n, reply_len, seq);
    if (rc == 0 && (n != reply_len || le32(r + n - 4) != seq))
        abort();
    /* requests built from the input: each step either fits or is refused */
    static const uint8_t wdata[255 * 8]; /* the most a write may take */
    struct lbp16_pkt p;
    lbp16_reset(&p);
    for (size_t i = 0; i + 6 <= n; i += 6) {
        unsigned space = r[i] & 7, sz = 1u << (r[i + 1] & 3), count = r[i + 2];
        uint16_t addr = (uint16_t)(r[i + 3] | r[i + 4] << 8);
        size_t len0 = p.len, rl0 = p.reply_len;
        int w = r[i + 5] & 1;
        rc = w ? lbp16_add_write(&p, space, sz, addr, count, r[i + 5] & 2, wdata)
               : lbp16_add_read(&p, space, sz, addr, count, r[i + 5] & 2);
        if (p.len > sizeof(p.buf) || p.reply_len > LBP16_MAX_PACKET)
            abort();
        if (rc == 0 && (w ? p.len != len0 + 4 + (size_t)count * sz || p.reply_len != rl0
                          : p.len != len0 + 4 || p.reply_len != rl0 + (size_t)count * sz))
            abort();
        if (rc != 0 && (p.len != len0 || p.reply_len != rl0))
            abort();
    }
    return 0;
}
