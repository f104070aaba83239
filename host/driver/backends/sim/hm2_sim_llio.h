/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_sim_llio.h - the llio of a virtual local-bus board (bin/vboard,
 * docs/hm2_sim.md): hm2 register access, queued transfers and FPGA
 * configuration over the vboard socket protocol.  No HAL calls, so the
 * hm2_sim module, bin/hm2pinout and the unit tests share it.
 *
 * One servo period costs one VB_READ round trip (every queued read) and
 * one VB_WRITE round trip (every queued write).  Each request carries the
 * host time from now_fn: under a simulated HAL clock the board runs in
 * lockstep with HAL and the whole session is deterministic.
 *
 * A transport failure (board killed, socket closed, no reply within the
 * timeout) is logged once; from then on every call fails at once with
 * -ENODEV, so a dead board never stalls a realtime thread.
 */
#ifndef HM2_SIM_LLIO_H
#define HM2_SIM_LLIO_H

#include <pthread.h>
#include <stdint.h>

#include "hm2/boards.h"
#include "hm2/hm2.h"
#include "hm2/llio.h"
#include "vboard_client.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_SIM_MAX_BOARDS 4

/* Host time in ns for a request (0: do not advance the board). */
typedef int64_t (*hm2_sim_now_fn)(void);

struct hm2_sim_queue {
    /* reads: the wire list (vb_xfer) and where each reply slice goes */
    struct vb_xfer *xfer;
    void **dest;
    int n, cap;
    size_t bytes;   /* total read bytes (reply length expected) */
    /* writes: the request payload as it goes on the wire */
    uint8_t *wbuf;
    size_t wlen, wcap;
};

struct hm2_sim_board {
    hm2_llio_t llio;           /* first: the core hands back &llio */
    vbc_t vbc;
    pthread_mutex_t lock;      /* read_gpio/write_gpio may run in another thread */
    int lock_ok;
    struct vb_hello hello;
    const struct hm2_board_info *info;
    struct hm2_sim_queue q;
    hm2_sim_now_fn now;
    hm2_log_fn log;
    void *log_ctx;
    int dead;                  /* transport failed: fail fast */
    int async_writes;          /* send queued writes without waiting for the
                                  reply (checked with the next request) */
    /* statistics (bench, tests) */
    uint64_t round_trips;
};

/* Connect to the board at socket `path`, check it is a configured-or-blank
 * local-bus board and, when `board` is non-NULL/non-empty, that it is that
 * board; fill the llio (name hm2_<board>.<index>).  0, or -errno after
 * logging why through log. */
int hm2_sim_setup(struct hm2_sim_board *sb, const char *path, const char *board, int index,
                  hm2_sim_now_fn now, hm2_log_fn log, void *log_ctx);
void hm2_sim_teardown(struct hm2_sim_board *sb);

#ifdef __cplusplus
}
#endif

#endif /* HM2_SIM_LLIO_H */
