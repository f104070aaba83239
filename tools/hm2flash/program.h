/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * program.h - hm2flash --program: volatile FPGA configuration with the
 * method each board has (program.c).
 */
#ifndef HM2FLASH_PROGRAM_H
#define HM2FLASH_PROGRAM_H

#include "hm2/boards.h"

struct program_req {
    const struct hm2_board_info *board; /* NULL: a Pluto-P */
    const char *addr;                   /* sim:SOCKET, or an EPP port spec */
    const char *file;                   /* .BIT (hm2 boards) or .rbf (Pluto-P) */
};

/* 0, or 1 after printing why (the FPGA untouched when the file is bad). */
int hm2flash_program(const struct program_req *q);

#endif /* HM2FLASH_PROGRAM_H */
