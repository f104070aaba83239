/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * flash_image.h - what hm2flash checks in a .BIT file before it writes a
 * board's flash: the FPGA part ('b' chunk) against the board's, the size
 * against the flash area, and the configuration data: a Xilinx bitstream
 * must carry the sync word; a virtual board's image (docs/vboard.md,
 * "Firmware files") must be whole, have a good CRC and name this board.
 */
#ifndef HM2FLASH_FLASH_IMAGE_H
#define HM2FLASH_FLASH_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "hm2/bitfile.h"

#define FLASH_VBFW_MAGIC 0x57464256u /* "VBFW" */

struct flash_image_info {
    int is_vboard;      /* a virtual board's image */
    char board[16];     /* its board and firmware names */
    char firmware[32];
};

/* 0, or -EINVAL/-EFBIG with the reason in err.  board ("5i25") and
 * fpga_part ("6slx9tqg144") may be NULL to skip those checks. */
int flash_image_check(const struct hm2_bitfile *bf, const char *board, const char *fpga_part,
                      uint32_t area_size, struct flash_image_info *info, char *err, size_t errlen);

#endif /* HM2FLASH_FLASH_IMAGE_H */
