/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * source_eth.c - hm2flash's Ethernet boards (7i92, 7i96S): hm2 registers
 * through the hm2_eth llio, the configuration flash through LBP16 memory
 * space 3 (spec/hostmot2.md 17.3): 0x0 flash address, 0x4 data (32-bit
 * words, the address advancing), 0x8 flash id, 0xC sector erase.  Writes
 * to the flash need the write-enable key (space 6 0x1A = 0x5A03) in the
 * same datagram, as mesaflash sends it.  Every datagram that changes the
 * flash ends with a read of the address register, so the reply confirms
 * the board has done it (a lost datagram is sent again: erasing or
 * programming the same data twice gives the same flash).
 */
#define _GNU_SOURCE
#include "source_eth.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2_eth_llio.h"

#define FL_ADDR 0x0u
#define FL_DATA 0x4u
#define FL_ID 0x8u
#define FL_ERASE 0xCu
#define RELOAD_PORT 0x1Eu    /* space 6: ICAP / reconfiguration words */
#define FW_VERSION 0x12u     /* space 7: firmware version (> 14: reload port) */
#define READ_WORDS 64u       /* per read command: 256 bytes, as mesaflash reads */
#define READ_CMDS 4u         /* read commands per datagram */
#define TIMEOUT_US 500000 /* a loaded host may take a while to answer */
#define ERASE_TIMEOUT_US 5000000 /* a sector erase takes up to 3 s on an M25P16 */
#define TRIES 5

static int efail(struct hm2_flash_io *io, int rc, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int efail(struct hm2_flash_io *io, int rc, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(io->err, sizeof(io->err), fmt, ap);
    va_end(ap);
    return rc;
}

static int transact(struct hm2_flash_io *io, const struct lbp16_pkt *p, uint8_t *reply,
                    int timeout_us, const char *what, uint32_t addr)
{
    struct hm2_eth_board *b = io->ops_ctx;
    int r = hm2_eth_transact(b, p, reply, timeout_us, TRIES);
    if (r)
        return efail(io, r, "%s: %s at 0x%06X over LBP16 failed (%s)", b->llio.name, what, addr,
                     r == -ETIMEDOUT ? "no reply from the board" : strerror(-r));
    return 0;
}

static int add_u32(struct lbp16_pkt *p, unsigned space, uint16_t reg, uint32_t v)
{
    uint8_t le[4] = {(uint8_t)v, (uint8_t)(v >> 8), (uint8_t)(v >> 16), (uint8_t)(v >> 24)};
    return lbp16_add_write(p, space, 4, reg, 1, 0, le);
}

static int add_write_enable(struct lbp16_pkt *p)
{
    uint8_t key[2] = {LBP16_WRITE_ENABLE_KEY & 0xFF, LBP16_WRITE_ENABLE_KEY >> 8};
    return lbp16_add_write(p, LBP16_SPACE_STATUS, 2, LBP16_STATUS_WRITE_ENABLE, 1, 0, key);
}

static int eth_identify(struct hm2_flash_io *io, uint8_t *sig)
{
    struct lbp16_pkt p;
    uint8_t rep[4];
    lbp16_reset(&p);
    if (lbp16_add_read(&p, LBP16_SPACE_FLASH, 4, FL_ID, 1, 0))
        return efail(io, -EINVAL, "flash id request does not fit");
    int r = transact(io, &p, rep, TIMEOUT_US, "reading the flash id", 0);
    if (!r)
        *sig = rep[0];
    return r;
}

static int eth_read(struct hm2_flash_io *io, uint32_t addr, uint8_t *buf, uint32_t n)
{
    uint8_t rep[READ_WORDS * 4 * READ_CMDS];
    if (addr % 4)
        return efail(io, -EINVAL, "flash read at 0x%06X: not word aligned", addr);
    for (uint32_t done = 0; done < n;) {
        uint32_t words = (n - done + 3) / 4;
        if (words > READ_WORDS * READ_CMDS)
            words = READ_WORDS * READ_CMDS;
        struct lbp16_pkt p;
        lbp16_reset(&p);
        int r = add_u32(&p, LBP16_SPACE_FLASH, FL_ADDR, addr + done);
        for (uint32_t w = 0; !r && w < words; w += READ_WORDS)
            r = lbp16_add_read(&p, LBP16_SPACE_FLASH, 4, FL_DATA,
                               words - w < READ_WORDS ? words - w : READ_WORDS, 0);
        if (r)
            return efail(io, -EINVAL, "flash read request does not fit");
        if ((r = transact(io, &p, rep, TIMEOUT_US, "flash read", addr + done)))
            return r;
        uint32_t got = words * 4 < n - done ? words * 4 : n - done;
        memcpy(buf + done, rep, got);
        done += got;
    }
    return 0;
}

static int eth_erase(struct hm2_flash_io *io, uint32_t addr)
{
    struct lbp16_pkt p;
    uint8_t rep[4];
    lbp16_reset(&p);
    int r = add_u32(&p, LBP16_SPACE_FLASH, FL_ADDR, addr);
    if (!r)
        r = add_write_enable(&p);
    if (!r)
        r = add_u32(&p, LBP16_SPACE_FLASH, FL_ERASE, 0);
    if (!r)
        r = lbp16_add_read(&p, LBP16_SPACE_FLASH, 4, FL_ADDR, 1, 0);
    if (r)
        return efail(io, -EINVAL, "erase request does not fit");
    return transact(io, &p, rep, ERASE_TIMEOUT_US, "sector erase", addr);
}

static int eth_program(struct hm2_flash_io *io, uint32_t addr, const uint8_t *data, uint32_t n)
{
    if (addr % 4)
        return efail(io, -EINVAL, "flash program at 0x%06X: not word aligned", addr);
    uint8_t words[HM2_FLASH_PAGE];
    memset(words, 0xFF, sizeof(words)); /* programming 1s leaves a bit as it is */
    memcpy(words, data, n);
    uint32_t count = (n + 3) / 4;
    struct lbp16_pkt p;
    uint8_t rep[4];
    lbp16_reset(&p);
    int r = add_u32(&p, LBP16_SPACE_FLASH, FL_ADDR, addr);
    if (!r)
        r = add_write_enable(&p);
    if (!r)
        r = lbp16_add_write(&p, LBP16_SPACE_FLASH, 4, FL_DATA, count, 0, words);
    if (!r)
        r = lbp16_add_read(&p, LBP16_SPACE_FLASH, 4, FL_ADDR, 1, 0);
    if (r)
        return efail(io, -EINVAL, "program request does not fit");
    r = transact(io, &p, rep, TIMEOUT_US, "page program", addr);
    uint32_t now = (uint32_t)rep[0] | (uint32_t)rep[1] << 8 | (uint32_t)rep[2] << 16 |
                   (uint32_t)rep[3] << 24;
    if (!r && now != addr + count * 4)
        return efail(io, -EIO, "%s: page program at 0x%06X: the flash address is 0x%06X "
                               "afterwards, not 0x%06X (write refused?)",
                     ((struct hm2_eth_board *)io->ops_ctx)->llio.name, addr, now,
                     addr + count * 4);
    return r;
}

/* Spartan-6: the ICAP words of an IPROG; Efinix: 0x0005, 0x000D (what
 * mesaflash --reload sends: tests/data/eth/mesaflash, the datagram logs). */
static int eth_reload(struct hm2_flash_io *io, int fallback)
{
    struct hm2_eth_board *b = io->ops_ctx;
    struct lbp16_pkt p;
    uint8_t rep[2];
    lbp16_reset(&p);
    lbp16_add_read(&p, LBP16_SPACE_INFO, 2, FW_VERSION, 1, 0);
    int r = transact(io, &p, rep, TIMEOUT_US, "reading the firmware version", 0);
    if (r)
        return r;
    unsigned ver = rep[0] | rep[1] << 8;
    if (ver <= 14)
        return efail(io, -ENOTSUP, "%s: its Ethernet firmware (version %u) cannot reload the "
                                   "FPGA (version 15 or later can): power cycle the board",
                     b->llio.name, ver);
    uint16_t words[16];
    size_t n;
    if (strcmp(b->info->fpga_part, "T20F256") == 0) {
        words[0] = 0x0005;
        words[1] = 0x000D;
        n = 2;
    } else {
        n = hm2_flash_iprog_words(fallback, words, 16);
    }
    lbp16_reset(&p);
    for (size_t i = 0; i < n; i++) {
        uint8_t le[2] = {(uint8_t)words[i], (uint8_t)(words[i] >> 8)};
        lbp16_add_write(&p, LBP16_SPACE_STATUS, 2, RELOAD_PORT, 1, 0, le);
    }
    /* no reply: the FPGA reconfigures */
    return transact(io, &p, NULL, TIMEOUT_US, "the reload command", 0);
}

static const struct hm2_flash_ops eth_ops = {eth_identify, eth_read, eth_erase, eth_program,
                                             eth_reload};

static void eth_log(void *ctx, int level, const char *line)
{
    char *why = ctx;
    if ((level == HM2_ERR || level == HM2_WARN) && !why[0])
        snprintf(why, 300, "%s", line);
}

int hm2flash_open_eth(const char *ip, struct hm2_flash_io *io, void **handle, char *why,
                      size_t whylen)
{
    if (whylen < 300)
        return -EINVAL;
    struct hm2_eth_board *b = calloc(1, sizeof(*b));
    if (!b) {
        snprintf(why, whylen, "out of memory");
        return -ENOMEM;
    }
    why[0] = 0;
    int r = hm2_eth_setup(b, ip, 0, eth_log, why);
    if (r) {
        if (!why[0])
            snprintf(why, whylen, "no board answers at %s (%s)", ip, strerror(-r));
        free(b);
        return r;
    }
    io->llio = &b->llio;
    io->ops = &eth_ops;
    io->ops_ctx = b;
    *handle = b;
    return 0;
}

const char *hm2flash_eth_board(void *handle)
{
    struct hm2_eth_board *b = handle;
    return b->info ? b->info->name : "";
}

void hm2flash_close_eth(void *handle)
{
    struct hm2_eth_board *b = handle;
    if (!b)
        return;
    hm2_eth_teardown(b, false);
    free(b);
}
