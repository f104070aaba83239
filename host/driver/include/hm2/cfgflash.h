/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * cfgflash.h - the SPI configuration flash of a Mesa board, reached through
 * the hm2 firmware's flash access registers over any llio (PCI window,
 * virtual board), and the Spartan-6 flash layout mesaflash uses: boot block
 * at 0, fallback image at 0x10000, user image at 0x100000.  See
 * docs/hm2flash.md.  No HAL calls.
 *
 * Every function returns 0 or a negative errno with the reason in io->err.
 */
#ifndef HM2_CFGFLASH_H
#define HM2_CFGFLASH_H

#include <stddef.h>
#include <stdint.h>

#include "hm2/llio.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_FLASH_REG_CTRL 0x0070u /* w: bit0 /CS; r: bit2 data available */
#define HM2_FLASH_REG_DATA 0x0074u /* w: shift a byte out; r: byte shifted in */
#define HM2_FLASH_REG_ICAP 0x0078u /* w: 16-bit ICAP words; r: 0x1CAB1CAB */
#define HM2_FLASH_ICAP_COOKIE 0x1CAB1CABu /* firmware that can --reload */
/* The boot status: a register of the virtual boards only (vboard(1)). */
#define HM2_FLASH_REG_BOOTSTS 0x007Cu
#define HM2_FLASH_DAV 0x04u

#define HM2_FLASH_BOOT_ADDR 0x000000u
#define HM2_FLASH_FALLBACK_ADDR 0x010000u
#define HM2_FLASH_USER_ADDR 0x100000u
#define HM2_FLASH_SECTOR 0x10000u
#define HM2_FLASH_PAGE 256u

/* Spartan-6 BOOTSTS bits (ICAP register read). */
#define HM2_BOOTSTS_VALID 0x01u
#define HM2_BOOTSTS_FALLBACK 0x02u
#define HM2_BOOTSTS_IPROG 0x04u
#define HM2_BOOTSTS_ID_ERROR 0x10u
#define HM2_BOOTSTS_CRC_ERROR 0x20u

struct hm2_flash_io;

/* A flash reached another way than through the SPI registers (an Ethernet
 * board's LBP16 memory space 3): when io->ops is set, these replace the SPI
 * commands; sector loops, progress, verify and the checks stay the same.
 * Each returns 0 or a negative errno with the reason in io->err. */
struct hm2_flash_ops {
    int (*identify)(struct hm2_flash_io *io, uint8_t *signature);
    int (*read)(struct hm2_flash_io *io, uint32_t addr, uint8_t *buf, uint32_t n);
    int (*erase_sector)(struct hm2_flash_io *io, uint32_t addr);
    /* n <= HM2_FLASH_PAGE, within one page */
    int (*program_page)(struct hm2_flash_io *io, uint32_t addr, const uint8_t *data, uint32_t n);
    int (*reload)(struct hm2_flash_io *io, int fallback);
};

struct hm2_flash_io {
    hm2_llio_t *llio;
    const struct hm2_flash_ops *ops; /* NULL: the hm2 SPI flash registers */
    void *ops_ctx;
    /* Wait ns nanoseconds (a real sleep, or a simulated clock's advance). */
    void (*delay_ns)(void *ctx, uint64_t ns);
    void *delay_ctx;
    /* Progress: phase ("Erasing", "Programming", "Verifying", "Reading"),
     * bytes done of total.  May be NULL. */
    void (*progress)(void *ctx, const char *phase, uint32_t done, uint32_t total);
    void *progress_ctx;
    /* Filled by hm2_flash_identify(). */
    uint8_t signature; /* RES electronic signature (0x14 = 16 Mbit) */
    uint32_t size;     /* bytes */
    uint32_t sector;   /* erase unit: 64 KiB; 32 KiB on a 1 Mbit part (M25P10-A) */
    /* statistics */
    uint64_t bytes_shifted;
    char err[256];
};

/* Size in bytes for an electronic signature (0x10 = 1 Mbit ... 0x16 =
 * 64 Mbit); 0 for an unknown one. */
uint32_t hm2_flash_size_of(uint8_t signature);
/* Its sector (erase unit) size. */
uint32_t hm2_flash_sector_of(uint8_t signature);
/* "16 Mbit" style text of a signature ("unknown" otherwise). */
const char *hm2_flash_size_text(uint8_t signature);

/* Read the electronic signature and set io->signature and io->size. */
int hm2_flash_identify(struct hm2_flash_io *io);
/* JEDEC ID (RDID): manufacturer, type, capacity (-ENOTSUP through ops). */
int hm2_flash_jedec(struct hm2_flash_io *io, uint8_t id[3]);

int hm2_flash_read(struct hm2_flash_io *io, uint32_t addr, uint8_t *buf, uint32_t n);
/* Erase the sectors covering [addr, addr + n), program the data, page by
 * page; each step waits for the part (timeout: 10 s per sector). */
int hm2_flash_write(struct hm2_flash_io *io, uint32_t addr, const uint8_t *data, uint32_t n);
/* Compare the flash at addr with data: 0 when equal; -EIO with the first
 * difference in io->err and *bad_addr. */
int hm2_flash_verify(struct hm2_flash_io *io, uint32_t addr, const uint8_t *data, uint32_t n,
                     uint32_t *bad_addr);

/* The boot block mesaflash writes for Spartan-6 boards (user 0x100000,
 * fallback 0x10000): its bytes, and whether the flash holds it. */
const uint8_t *hm2_flash_boot_block(size_t *len);
int hm2_flash_boot_block_ok(struct hm2_flash_io *io, int *ok);

/* Make the FPGA reconfigure from the flash through ICAP (IPROG), from the
 * boot block (fallback = 0) or straight from the fallback image. */
int hm2_flash_reload(struct hm2_flash_io *io, int fallback);
/* The Spartan-6 ICAP words of that reload, mesaflash 3.4.6's (two dummy
 * words, sync, GENERAL1/2 = the address to load (0, or the fallback at
 * 0x10000) with read opcode 0x0B, CMD = IPROG, four NOOPs): the count
 * written to out, 0 if max is too small. */
size_t hm2_flash_iprog_words(int fallback, uint16_t *out, size_t max);
/* The boot status (BOOTSTS bits) a virtual board reports at 0x7C (-ENOTSUP
 * through ops; not on Mesa's firmware). */
int hm2_flash_boot_status(struct hm2_flash_io *io, uint32_t *bootsts);

#ifdef __cplusplus
}
#endif

#endif /* HM2_CFGFLASH_H */
