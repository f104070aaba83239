/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_sim_inproc.h - the llio of a virtual local-bus board that runs inside
 * this process (lib/libvboard_inproc.so, vboard/inproc.h; docs/hm2_sim.md
 * "IN-PROCESS BOARDS").  The same board and the same time rule as the
 * socket llio (hm2_sim_llio.h), without the socket: a servo period's
 * queued reads are one call that fills the driver's buffers directly, its
 * queued writes one call.  No HAL calls.
 */
#ifndef HM2_SIM_INPROC_H
#define HM2_SIM_INPROC_H

#include <pthread.h>
#include <stdint.h>

#include "hm2/boards.h"
#include "hm2/hm2.h"
#include "hm2/llio.h"
#include "hm2_sim_llio.h"
#include "vboard/inproc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The loaded board library (one per module). */
struct hm2_sim_inproc_lib {
    void *dl;
    const vbi_api_t *api;
    char path[512];
};

/* Load the library: `path` when non-NULL/non-empty, else
 * HM2_SIM_INPROC_LIB from the environment, else libvboard_inproc.so in the
 * lib/ folder above the module that calls this (lib/rtlib/../).  0, or
 * -errno after logging what was tried and why it failed. */
int hm2_sim_inproc_lib_open(struct hm2_sim_inproc_lib *lib, const char *path, hm2_log_fn log,
                            void *log_ctx);
void hm2_sim_inproc_lib_close(struct hm2_sim_inproc_lib *lib);

struct hm2_sim_inproc {
    hm2_llio_t llio; /* first: the core hands back &llio */
    const vbi_api_t *api;
    vbi_board_t *vb;
    pthread_mutex_t lock; /* read_gpio/write_gpio may run in another thread */
    int lock_ok;
    struct vb_hello hello;
    const struct hm2_board_info *info;
    hm2_sim_now_fn now;
    hm2_log_fn log;
    void *log_ctx;
    /* queued reads: transfers and destinations (filled in place) */
    struct vb_xfer *rx;
    void **rdest;
    int rn, rcap;
    /* queued writes: transfers, data copied at queue time, pointers to it */
    struct vb_xfer *wx;
    size_t *woff;
    const void **wsrc;
    int wn, wcap;
    uint8_t *wbuf;
    size_t wlen, wbcap;
    /* statistics: queued flushes and the wall ns spent in those calls */
    int stats;                   /* 1: measure the flushes (below) */
    uint64_t read_flushes, write_flushes;
    uint64_t flush_ns;           /* wall ns in the flush calls */
    uint64_t model_ns;           /* of it, in the board model (library's count) */
    uint64_t words_read, words_written;
};

/* A new board `board` with the built-in firmware `firmware` (NULL/"" =
 * blank: the config string's firmware= programs it) from `lib`; fill the
 * llio (name hm2_<board>.<index>).  0, or -errno after logging why. */
int hm2_sim_inproc_setup(struct hm2_sim_inproc *ib, const struct hm2_sim_inproc_lib *lib,
                         const char *board, const char *firmware, int index, hm2_sim_now_fn now,
                         hm2_log_fn log, void *log_ctx);
/* Wire output pin `from` to input pin `to` for every FROM:TO[:inv] word of
 * `spec` (space separated).  0, or -errno after logging the bad word. */
int hm2_sim_inproc_loops(struct hm2_sim_inproc *ib, const char *spec);
/* With stats set: one line on where the servo periods' time went: per queued
 * read+write pair, the ns spent in the calls to the board, of them in the
 * board model (clock edges of the bus cycles and of the time advance), and
 * the rest (the transport: checks, copies, calls); words moved. */
void hm2_sim_inproc_report(struct hm2_sim_inproc *ib);
/* Run the board free with the wall clock on its own thread (vboard
 * --freerun's rule).  0, or -errno after logging why. */
int hm2_sim_inproc_freerun(struct hm2_sim_inproc *ib);
void hm2_sim_inproc_teardown(struct hm2_sim_inproc *ib);

#ifdef __cplusplus
}
#endif

#endif /* HM2_SIM_INPROC_H */
