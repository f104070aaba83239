/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * llio_image.h - an llio backend over a register image in memory: the
 * 64 KiB hm2 address space as RAM (reads return it, writes store into it).
 * Used by hm2pinout (image files), hm2_test and the unit tests.  It can
 * inject read failures and can run in queued mode to exercise that path.
 */
#ifndef HM2_LLIO_IMAGE_H
#define HM2_LLIO_IMAGE_H

#include <stdint.h>

#include "hm2/boards.h"
#include "hm2/llio.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_IMAGE_SIZE 0x10000u
#define HM2_IMAGE_MAX_QUEUE 256

struct hm2_image_llio {
    hm2_llio_t llio;
    uint8_t mem[HM2_IMAGE_SIZE];
    /* read failure injection: a read touching [fail_lo, fail_hi] -> -EIO */
    int32_t fail_lo, fail_hi;
    /* 1: writes are dropped (LinuxCNC hm2_test behaviour) */
    int discard_writes;
    /* statistics */
    unsigned reads, writes, flushes;
    /* queued mode (enabled by hm2_image_llio_set_queued) */
    struct {
        uint32_t addr;
        void *buf;
        size_t size;
    } rq[HM2_IMAGE_MAX_QUEUE];
    int nrq;
    struct {
        uint32_t addr;
        uint8_t data[64];
        size_t size;
    } wq[HM2_IMAGE_MAX_QUEUE];
    int nwq;
    /* optional hook run after every write (tests model register side effects) */
    void (*on_write)(struct hm2_image_llio *im, uint32_t addr, uint32_t value);
    void *user;
};

/* Zeroed image, no failures, immediate mode.  name is the full llio name. */
void hm2_image_llio_init(struct hm2_image_llio *im, const char *name);
/* Take geometry from the board table and name it hm2_<board>.<index>. */
void hm2_image_llio_set_board(struct hm2_image_llio *im, const struct hm2_board_info *b,
                              int index);
void hm2_image_llio_set_queued(struct hm2_image_llio *im, int on);
/* Load an image file: 65536 bytes = the whole register space; 1024 bytes =
 * the IDROM RAM alone (placed at 0x400 with the standard ID block
 * synthesized).  0 or -errno with a message in err. */
int hm2_image_llio_load(struct hm2_image_llio *im, const char *path, char *err, size_t errlen);

static inline void hm2_image_put32(struct hm2_image_llio *im, uint32_t addr, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        im->mem[(addr + (uint32_t)i) & 0xFFFFu] = (uint8_t)(v >> (8 * i));
}
static inline uint32_t hm2_image_get32(const struct hm2_image_llio *im, uint32_t addr)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++)
        v |= (uint32_t)im->mem[(addr + (uint32_t)i) & 0xFFFFu] << (8 * i);
    return v;
}

#ifdef __cplusplus
}
#endif

#endif /* HM2_LLIO_IMAGE_H */
