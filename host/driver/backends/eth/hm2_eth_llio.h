/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_eth_llio.h - the llio of a Mesa Ethernet board (7i92, 7i96S, ...):
 * hm2 register access over LBP16/UDP (docs/hm2_eth.md).  No HAL calls, so
 * the hm2_eth module, bin/hm2pinout, bin/hm2flash and the unit tests share
 * it.
 *
 * One servo period costs one read datagram (every queued read plus the
 * sequence-number bookkeeping; one reply) and one write datagram (every
 * queued write plus the write sequence number; no reply).  A read whose
 * reply does not come within packet-read-timeout, or a reply that shows
 * the previous write datagram was lost, is a packet error: the cycle keeps
 * the previous cycle's data, packet-error is set for that cycle and
 * packet-error-level rises by packet-error-increment (it falls by
 * packet-error-decrement in a good cycle).  At packet-error-limit the read
 * fails (the hostmot2 core sets io_error and stops writing) until io_error
 * is cleared.
 *
 * The read can be split (hm2_<board>.<n>.read-request, hostmot2(9)): the
 * request goes out when read-request runs and read only waits for the
 * reply; packet-read-timeout then counts from the request.
 */
#ifndef HM2_ETH_LLIO_H
#define HM2_ETH_LLIO_H

#include <netinet/in.h>
#include <stdbool.h>
#include <stdint.h>
#include <sys/types.h>

#include "hm2/boards.h"
#include "hm2/hm2.h"
#include "hm2/llio.h"
#include "lbp16.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_ETH_MAX_BOARDS 4
#define HM2_ETH_MAX_QUEUED 64

/* The packet-error pins and parameters (hm2_eth(9)).  The module keeps
 * this struct in HAL memory (linking a pin changes its pointer here) and
 * points hm2_eth_board.pins at it; other users get local_pins, pointing
 * at hm2_eth_board.local. */
struct hm2_eth_errpins {
    volatile bool *error, *exceeded;
    volatile int32_t *level;
    volatile uint32_t *total; /* u32 I/O, as LinuxCNC 2.9 exports it */
    volatile int32_t *limit, *increment, *decrement, *read_timeout;
};

struct hm2_eth_errvals {
    bool error, exceeded;
    int32_t level, limit, increment, decrement, read_timeout;
    uint32_t total;
};

struct hm2_eth_stats {
    uint64_t read_packets, write_packets, replies, timeouts, stale, write_losses;
    uint64_t rt_reads; /* synchronous reads made while running (extra packets) */
};

struct hm2_eth_board {
    hm2_llio_t llio; /* first: the core hands back &llio */
    int fd;
    struct sockaddr_in peer;
    char ip[16];
    char lbp16_name[17]; /* "7I96S" */
    uint8_t mac[6];
    const struct hm2_board_info *info;
    /* per-cycle queues */
    struct lbp16_pkt rpkt, wpkt;
    struct {
        void *dest;
        size_t size;
    } rq[HM2_ETH_MAX_QUEUED];
    int nrq;
    uint32_t read_seq, write_seq;
    /* the servo read sent (request_queued_reads) and not yet received */
    struct {
        bool pending;
        int send_err;     /* 0, or why the request could not be sent */
        int nrq;          /* queued reads it carries */
        long timeout_ns;  /* packet-read-timeout, counted from the send */
        int64_t deadline; /* monotonic ns */
        ssize_t kept;     /* > 0: its reply, seen early by a synchronous read */
        uint8_t reply[LBP16_MAX_PACKET + 1];
    } req;
    uint32_t sync_tag; /* last tag of a synchronous request */
    /* errors */
    struct hm2_eth_errpins *pins, local_pins;
    struct hm2_eth_errvals local;
    bool silent;     /* a lost-reply streak is being reported */
    bool running;    /* the servo cycle has started (reads are queued) */
    struct hm2_eth_stats stats;
    hm2_log_fn log;
    void *log_ctx;
};

/* Open the board at IPv4 address `ip` (dotted quad), ask it for its name
 * and MAC, check this driver knows it and fill the llio (name
 * hm2_<board>.<index>, connectors, per-pin names).  0, or -errno after
 * logging why. */
int hm2_eth_setup(struct hm2_eth_board *b, const char *ip, int index, hm2_log_fn log,
                  void *log_ctx);
/* Watchdog bite (outputs safe), then close. */
void hm2_eth_teardown(struct hm2_eth_board *b, bool bite);

/* LBP16 name ("7I96S") -> board table entry; NULL if unknown. */
const struct hm2_board_info *hm2_eth_board_of(const char *lbp16_name);

/* One synchronous request: send `p` with a fresh tag (lbp16_add_sync_tag),
 * wait up to timeout_us for the reply carrying that tag and copy its
 * p->reply_len bytes of data into `reply` (tries times).  0 or
 * -ETIMEDOUT/-ENOSPC/-errno.  Requests without reads are only sent. */
int hm2_eth_transact(struct hm2_eth_board *b, const struct lbp16_pkt *p, uint8_t *reply,
                     int timeout_us, int tries);

/* The read timeout in ns for a thread of period_ns (hm2_eth(9)). */
long hm2_eth_read_timeout_ns(int32_t param, long period_ns);

#ifdef __cplusplus
}
#endif

#endif /* HM2_ETH_LLIO_H */
