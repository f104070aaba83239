/* SPDX-License-Identifier: GPL-2.0-or-later */
/* fake_board - a tiny virtual board for the vbclient / hm2_sim unit tests:
 * one client at a time, a 64 KiB register file, scripted misbehaviour. */
#ifndef FAKE_BOARD_H
#define FAKE_BOARD_H

#include <pthread.h>
#include <stdint.h>

#include "vboard/proto.h"

enum fake_fault {
    FAKE_OK = 0,
    FAKE_CLOSE,      /* close the connection instead of answering */
    FAKE_SILENT,     /* read the request, never answer */
    FAKE_BAD_SEQ,    /* answer with a wrong sequence number */
    FAKE_STALL,      /* stop reading the socket until stall_release is set */
};

struct fake_board {
    char path[108];
    int listen_fd;
    pthread_t thread;
    /* identity */
    uint32_t bus, state;
    char board[16];
    /* behaviour: fault applies from request number fault_at on (1-based) */
    enum fake_fault fault;
    int fault_at;
    volatile int stall_release;
    /* observations */
    int requests;
    int reads, writes, configs;
    uint32_t last_xfers;        /* xfers in the last READ/WRITE */
    uint64_t last_time_ns;
    uint8_t regs[65536];
};

/* Start serving on a fresh socket in /tmp; 0 or -1. */
int fake_board_start(struct fake_board *fb, const char *board, uint32_t bus, uint32_t state);
void fake_board_stop(struct fake_board *fb);

#endif
