/* SPDX-License-Identifier: GPL-2.0-or-later */
/* flash_image.c - checks of a .BIT file before it goes into a board's
 * configuration flash (flash_image.h). */
#define _POSIX_C_SOURCE 200809L
#include "flash_image.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "hm2/cfgflash.h"

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* zlib CRC-32, as the virtual boards' images carry it. */
static uint32_t crc32_of(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

static int has_sync_word(const uint8_t *p, size_t n)
{
    for (size_t i = 0; i + 4 <= n && i < 256; i++)
        if (p[i] == 0xAA && p[i + 1] == 0x99 && p[i + 2] == 0x55 && p[i + 3] == 0x66)
            return 1;
    return 0;
}

int flash_image_check(const struct hm2_bitfile *bf, const char *board, const char *fpga_part,
                      uint32_t area_size, struct flash_image_info *info, char *err, size_t errlen)
{
    memset(info, 0, sizeof(*info));
    if (fpga_part && *fpga_part && strcasecmp(bf->part, fpga_part) != 0) {
        snprintf(err, errlen, "wrong bitfile destination device: %s, should be %s (the %s has "
                              "a %s FPGA)", bf->part, fpga_part, board, fpga_part);
        return -EINVAL;
    }
    if (bf->size == 0) {
        snprintf(err, errlen, "the bitfile holds no configuration data");
        return -EINVAL;
    }
    if (bf->size > area_size) {
        snprintf(err, errlen, "the configuration (%u bytes) does not fit the %u-byte flash area",
                 bf->size, area_size);
        return -EFBIG;
    }
    const uint8_t *p = bf->data;
    if (bf->size >= 4 && le32(p) == FLASH_VBFW_MAGIC) {
        /* A virtual board's image: whole, CRC good, and for this board. */
        if (bf->size < 68 || le32(p + 8) != bf->size) {
            snprintf(err, errlen, "the virtual-board image is truncated or padded (%u bytes, its "
                                  "header says %u)", bf->size, bf->size >= 12 ? le32(p + 8) : 0);
            return -EINVAL;
        }
        if (crc32_of(p, 64) != le32(p + 64)) {
            snprintf(err, errlen, "the virtual-board image is corrupt (CRC-32 mismatch)");
            return -EINVAL;
        }
        info->is_vboard = 1;
        snprintf(info->board, sizeof(info->board), "%.15s", (const char *)p + 16);
        snprintf(info->firmware, sizeof(info->firmware), "%.31s", (const char *)p + 32);
        if (board && *board && strcasecmp(info->board, board) != 0) {
            snprintf(err, errlen, "the bitfile is a firmware for a %s, not for a %s",
                     info->board, board);
            return -EINVAL;
        }
        return 0;
    }
    if (fpga_part && strncasecmp(fpga_part, "T20", 3) == 0)
        return 0; /* an Efinix bitstream: no Xilinx sync word to look for */
    if (!has_sync_word(p, bf->size)) {
        snprintf(err, errlen, "the configuration data has no sync word (0xAA995566): not an FPGA "
                              "bitstream");
        return -EINVAL;
    }
    return 0;
}
