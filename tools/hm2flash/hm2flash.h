/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2flash.h - the board hm2flash works on: an llio reached through a
 * source (sim:SOCKET, pci:[ADDR], an Ethernet board's IP address), the flash access on it, a clock (the board's
 * simulated one for a virtual board) and the progress display.
 */
#ifndef HM2FLASH_H
#define HM2FLASH_H

#include <stdint.h>

#include "hm2/boards.h"
#include "hm2/cfgflash.h"

struct hm2flash_board {
    const struct hm2_board_info *board;
    char display_name[16];  /* "5I25" */
    char description[200];  /* "5I25 (virtual board at /tmp/vb.sock)" */
    char firmware[64];
    char source[160];
    struct hm2_flash_io io;
    void *handle;           /* the source's state */
    int is_pci;             /* pci: source (real time), else sim: (board time) */
    int is_eth;             /* an Ethernet board (LBP16; real time) */
    /* the flash layout of the board's FPGA family */
    uint32_t user_addr, fallback_addr;
    int boot_block;         /* Spartan-6: the boot block at 0 selects the images */
    /* progress display */
    int tty;
    const char *phase;
    uint32_t area_addr;     /* for the phase headers */
    uint64_t phase_start_ns;
    uint32_t last_done, last_total;
    int last_pct;
    char why[300];          /* reason of a failed open */
};

int hm2flash_open(struct hm2flash_board *bd, const char *device, const char *addr);
/* After a reload: connect again and read the firmware it runs now. */
int hm2flash_reopen(struct hm2flash_board *bd);
void hm2flash_close(struct hm2flash_board *bd);
/* ns on the board's clock (simulated for a virtual board). */
uint64_t hm2flash_now_ns(struct hm2flash_board *bd);

void hm2flash_progress_begin(struct hm2flash_board *bd);
void hm2flash_progress_end(struct hm2flash_board *bd);

#endif /* HM2FLASH_H */
