/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * vboard/inproc.h - the virtual local-bus board as a library
 * (lib/libvboard_inproc.so, docs/hm2_sim.md "IN-PROCESS BOARDS").
 *
 * The same board the vboard program serves on a socket (a LocalBusBoard
 * with its Verilated firmware), called directly: a servo period's reads and
 * writes are function calls, no bytes are framed or copied through a
 * kernel.  The hm2_sim module dlopen()s the library when it is loaded with
 * inproc=1, so the socket-only users never map the Verilated models.
 *
 * One entry point, vbi_get_api(), returns a table of functions; the caller
 * checks `abi` against VBI_ABI before using anything else.
 *
 * Time follows the socket protocol's lockstep rule (vboard/proto.h): every
 * call carries the host time in ns; 0 does not advance the board; the first
 * non-zero time sets the epoch (board time continues where it is); later
 * calls first run the FPGA clocks up to host_time - epoch.  A jump of more
 * than 60 s fails with -ERANGE and re-takes the epoch at the next call.
 * freerun(b, 1) instead runs the board on a thread of its own with the wall
 * clock, as `vboard --freerun` does (host times are then ignored; a board
 * slower than real time runs as fast as it can without trying to catch up
 * more than 50 ms); freerun(b, 0) stops that thread.
 *
 * Errors return a negative errno; the message (what failed, on which board,
 * why) is then in error(b).  Nothing of a failed call is applied except the
 * time advance.  Calls on one board are serialized by the library (its own
 * board thread included); error(b) belongs to the thread that made the last
 * failing call, so one caller thread per board (the caller locks).
 */
#ifndef VBOARD_INPROC_H
#define VBOARD_INPROC_H

#include <stddef.h>
#include <stdint.h>

#include "vboard/proto.h"

#ifdef __cplusplus
extern "C" {
#endif

#define VBI_ABI 2u
#define VBI_ENTRY "vbi_get_api"
#define VBI_LIBRARY "libvboard_inproc.so"

typedef struct vbi_board vbi_board_t;

/* Counters of one board since it was opened. */
struct vbi_stats {
    uint64_t calls;       /* read/write/config/run calls */
    uint64_t board_ns;    /* wall ns spent inside the board model (clock
                             advance and bus cycles), measured by the library */
    uint64_t read_words;  /* 32-bit words read / written on the local bus */
    uint64_t write_words;
};

typedef struct vbi_api {
    uint32_t abi; /* VBI_ABI */
    /* A new board `board` ("5i20") configured with the built-in firmware
     * `firmware` ("SVST8_4"; NULL or "" = blank).  NULL on failure, with
     * the reason in err (always NUL-terminated). */
    vbi_board_t *(*open)(const char *board, const char *firmware, char *err, size_t errlen);
    void (*close)(vbi_board_t *b);
    const char *(*error)(const vbi_board_t *b);
    /* What VB_HELLO answers (lockstep = 1). */
    void (*hello)(vbi_board_t *b, struct vb_hello *out);
    /* n transfers; transfer i reads x[i].size bytes at x[i].addr into
     * dest[i] (reads pipelined back to back, as VB_READ). */
    int (*read)(vbi_board_t *b, uint64_t host_time, const struct vb_xfer *x, void *const *dest,
                size_t n);
    /* n transfers; transfer i writes x[i].size bytes from src[i] (VB_WRITE). */
    int (*write)(vbi_board_t *b, uint64_t host_time, const struct vb_xfer *x,
                 const void *const *src, size_t n);
    /* The configuration port (VB_CONFIG); bits = a .BIT 'e' chunk. */
    int (*config)(vbi_board_t *b, uint64_t host_time, uint32_t op, const uint8_t *bits,
                  size_t len, struct vb_config_status *st);
    /* Wire output pin `from` into input pin `to` (VB_LOOP). */
    int (*loop)(vbi_board_t *b, uint32_t from, uint32_t to, int invert);
    /* count pins from `first` (VB_PROBE). */
    int (*probe)(vbi_board_t *b, uint32_t first, uint32_t count, struct vb_pin *out);
    uint64_t (*now_ns)(const vbi_board_t *b);
    void (*stats)(const vbi_board_t *b, struct vbi_stats *out);
    /* 1: run free with the wall clock on a board thread; 0: lockstep. */
    int (*freerun)(vbi_board_t *b, int on);
} vbi_api_t;

typedef const vbi_api_t *(*vbi_get_api_fn)(void);
const vbi_api_t *vbi_get_api(void);

#ifdef __cplusplus
}
#endif

#endif /* VBOARD_INPROC_H */
