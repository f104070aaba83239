/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * lbp16.h - LBP16 datagrams on the host side (spec/hostmot2.md 17.3):
 * building request packets and checking replies.  No sockets here, so the
 * reply checks can be unit-tested and fuzzed on their own.
 */
#ifndef HM2_ETH_LBP16_H
#define HM2_ETH_LBP16_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define LBP16_PORT 27181
#define LBP16_MAX_PACKET 1472       /* UDP payload of one 1500-byte frame */
#define LBP16_MAX_COUNT 127

#define LBP16_WRITE 0x8000u
#define LBP16_ADDR 0x4000u
#define LBP16_INFO 0x2000u
#define LBP16_SPACE(s) ((unsigned)(s) << 10)
#define LBP16_SIZE8 0x0000u
#define LBP16_SIZE16 0x0100u
#define LBP16_SIZE32 0x0200u
#define LBP16_INC 0x0080u

enum lbp16_space {
    LBP16_SPACE_HM2 = 0,
    LBP16_SPACE_ETH_CHIP = 1,
    LBP16_SPACE_EEPROM = 2,
    LBP16_SPACE_FLASH = 3,
    LBP16_SPACE_TIMERS = 4,
    LBP16_SPACE_STATUS = 6,
    LBP16_SPACE_INFO = 7,
};

/* Timer-space scratch words the servo cycle uses as sequence numbers. */
#define LBP16_SCRATCH_READ_SEQ 0x10
#define LBP16_SCRATCH_WRITE_SEQ 0x14
#define LBP16_SCRATCH_SYNC_TAG 0x18 /* tag echoed by synchronous requests */
#define LBP16_TIMER_WAIT_US 0x02    /* write: the board waits that many us */
#define LBP16_STATUS_RX_PACKETS 0x08
#define LBP16_STATUS_WRITE_ENABLE 0x1A
#define LBP16_WRITE_ENABLE_KEY 0x5A03

struct lbp16_pkt {
    uint8_t buf[LBP16_MAX_PACKET];
    size_t len;       /* bytes of commands so far */
    size_t reply_len; /* bytes the reply will carry */
};

void lbp16_reset(struct lbp16_pkt *p);
/* Append a read of `count` elements of `size` bytes (2 or 4) from `space`
 * at `addr` (inc: incrementing).  -ENOSPC when the request or its reply
 * would not fit in one datagram, -EINVAL for a bad count/size. */
int lbp16_add_read(struct lbp16_pkt *p, unsigned space, unsigned size, uint16_t addr,
                   unsigned count, int inc);
/* Append a write of `count` elements from `data` (little-endian). */
int lbp16_add_write(struct lbp16_pkt *p, unsigned space, unsigned size, uint16_t addr,
                    unsigned count, int inc, const void *data);

/* The servo cycle's bookkeeping, appended after the hm2 reads of a read
 * packet: the board's RX packet count (2 bytes), the read sequence number
 * written to scratch and both sequence numbers read back (8 bytes). */
#define LBP16_READ_TAIL_REPLY 10
/* The tails are appended whole or not at all (-ENOSPC, packet unchanged). */
int lbp16_add_read_tail(struct lbp16_pkt *p, uint32_t read_seq);
/* Appended to a write packet: the write sequence number to scratch. */
int lbp16_add_write_tail(struct lbp16_pkt *p, uint32_t write_seq);

/* Appended to a synchronous request: `tag` written to scratch 0x18 and
 * read back, so its reply ends with the tag (4 bytes) and a late reply to
 * an earlier request of the same size is told apart. */
#define LBP16_SYNC_TAIL_REPLY 4
int lbp16_add_sync_tag(struct lbp16_pkt *p, uint32_t tag);
/* 0 if the n-byte reply is the one to a request of reply_len bytes (tag
 * included) carrying `tag`; -EMSGSIZE wrong length, -ESTALE other tag. */
int lbp16_check_sync_reply(const uint8_t *r, size_t n, size_t reply_len, uint32_t tag);

/* What a servo-cycle read reply says. */
struct lbp16_reply_check {
    uint16_t rx_packets;
    uint32_t read_seq;  /* echoed */
    uint32_t write_seq; /* echoed */
};
/* Check a servo-cycle read reply of n bytes against the packet it answers
 * (reply_len, read_seq): 0 = it is that reply (fields filled); -EMSGSIZE =
 * wrong length (not this packet's reply); -ESTALE = right length but
 * another cycle's sequence number (a late reply). */
int lbp16_check_read_reply(const uint8_t *r, size_t n, size_t reply_len, uint32_t read_seq,
                           struct lbp16_reply_check *out);

#ifdef __cplusplus
}
#endif

#endif /* HM2_ETH_LBP16_H */
