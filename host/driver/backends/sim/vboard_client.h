/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * vboard_client.h - the C client of the virtual board's socket protocol
 * (sim/verilator/include/vboard/proto.h), shared by the hm2_sim llio and
 * the sim: epp_port backend.  No HAL calls; usable from tools and tests.
 *
 * A client owns one connection.  vbc_call() sends one request and waits for
 * its reply (timeout per call, default 5 s).  After a transport failure
 * (board gone, timeout, garbage) the connection is closed and every later
 * call fails fast with -ENODEV until vbc_reconnect() succeeds; the error
 * text says what happened once.
 */
#ifndef VBOARD_CLIENT_H
#define VBOARD_CLIENT_H

#include <stddef.h>
#include <stdint.h>

#include "vboard/proto.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vbc {
    int fd;                  /* -1 when not connected */
    char path[108];          /* sun_path */
    uint32_t seq;
    int timeout_ms;
    int spin_us;             /* busy-poll this long for a reply before
                                sleeping (0 = never spin) */
    /* Reply payload of the last call (grown as needed, owned here). */
    uint8_t *rx;
    size_t rx_len, rx_cap;
    /* Request assembly buffer (vbc_req_* helpers). */
    uint8_t *tx;
    size_t tx_len, tx_cap;
    uint64_t board_time_ns;  /* from the last reply */
    /* A request sent by vbc_post() whose reply is still to be read. */
    int posted;
    uint16_t posted_type;
    uint32_t posted_seq;
    char err[512];           /* last error text */
} vbc_t;

/* Connect to the board's socket.  0, or -errno with the reason in c->err. */
int vbc_open(vbc_t *c, const char *path);
void vbc_close(vbc_t *c);
int vbc_reconnect(vbc_t *c);

/* Request assembly: start, append bytes, then vbc_send(type, time).  The
 * reply payload is c->rx[0..rx_len).  Returns the reply status (0, or the
 * board's -errno with its message in c->err), or a transport -errno
 * (-ENODEV, -ETIMEDOUT, -EPROTO) with the reason in c->err. */
void vbc_req_start(vbc_t *c);
int vbc_req_put(vbc_t *c, const void *data, size_t n);
int vbc_send(vbc_t *c, uint16_t type, uint64_t host_time_ns);

/* Send the assembled request without waiting for its reply (a write whose
 * completion the caller does not need, as hm2_eth does not wait for write
 * acknowledgements).  At most one request is outstanding: the reply is read
 * and checked by the next vbc_send()/vbc_post()/vbc_collect(), which
 * returns its error (board -errno, with "(reply to an earlier request
 * ...)" in c->err) instead of sending anything.  The board serves one
 * connection's requests in order, so a later request sees the effect. */
int vbc_post(vbc_t *c, uint16_t type, uint64_t host_time_ns);
/* Read and check the reply of a posted request, if any.  0 or -errno. */
int vbc_collect(vbc_t *c);

/* A lockstep board (the vboard default) runs its FPGA clocks up to the time
 * each request carries: it needs a client on HAL's simulated clock.  On the
 * wall clock it would have to simulate every real second and fall behind
 * until calls time out.  Returns 0 when the pairing works, else -EINVAL
 * with what is wrong and what to do in c->err. */
int vbc_check_clock(vbc_t *c, const struct vb_hello *h, int client_on_simclock);

/* Remove the socket file at `path` if it is a socket nobody listens on any
 * more (a board killed with SIGKILL cannot remove its own).  A live board's
 * socket, or anything that is not a socket, is left alone.  1 when removed. */
int vbc_remove_stale(const char *path);

/* One-shot helpers. */
int vbc_call(vbc_t *c, uint16_t type, uint64_t host_time_ns, const void *payload, size_t n);
int vbc_hello(vbc_t *c, struct vb_hello *out);

#ifdef __cplusplus
}
#endif

#endif /* VBOARD_CLIENT_H */
