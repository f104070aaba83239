/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Mesa PCI boards as hm2 llios (see hm2_pci_core.h). */
#define _GNU_SOURCE
#include "hm2_pci_core.h"

#include <endian.h>
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "hm2/bitfile.h"

#define P9030 HM2_PCI_PLX9030
#define P9054 HM2_PCI_PLX9054
#define NATIVE HM2_PCI_NATIVE
#define PLX HM2_PCI_VENDOR_PLX
#define MESA HM2_PCI_VENDOR_MESA

/* spec §16 (vendor:device, subsystem vendor:device).  The 9056 of the
 * 3x20 carriers is programmed like the 9054. */
static const struct hm2_pci_id ids[] = {
    {PLX, 0x9030, PLX, 0x3131, "5i20", "5i20", P9030, 0},
    {PLX, 0x9030, PLX, 0x3132, "4i65", "4i65", P9030, 0},
    {PLX, 0x9054, PLX, 0x3312, "5i21", "5i21", P9054, 0},
    {PLX, 0x9054, PLX, 0x3314, "5i22-1.0M", "5i22", P9054, 0},
    {PLX, 0x9054, PLX, 0x3313, "5i22-1.5M", "5i22", P9054, 0},
    {PLX, 0x9054, PLX, 0x3315, "5i23", "5i23", P9054, 0},
    {PLX, 0x9054, PLX, 0x3311, "4i68", "4i68", P9054, 0},
    {PLX, 0x9054, PLX, 0x3133, "4i68", "4i68", P9054, 1},
    {PLX, 0x9054, PLX, 0x3472, "4I69-16", "4i69", P9054, 0},
    {PLX, 0x9054, PLX, 0x3473, "4I69-25", "4i69", P9054, 0},
    {PLX, 0x9056, PLX, 0x3427, "3x20-1.0M", "3x20", P9054, 0},
    {PLX, 0x9056, PLX, 0x3428, "3x20-1.5M", "3x20", P9054, 0},
    {PLX, 0x9056, PLX, 0x3429, "3x20-2.0M", "3x20", P9054, 0},
    {MESA, 0x5124, MESA, 0x5124, "5i24", "5i24", NATIVE, 0},
    {MESA, 0x5125, MESA, 0x5125, "5i25", "5i25", NATIVE, 0},
    {MESA, 0x6125, MESA, 0x6125, "6i25", "6i25", NATIVE, 0},
};

/* Boards hm2_pci knows that the shared table (llio/boards.c) does not
 * (spec §16 "Other IDs known to hm2_pci").  LED counts are not in the
 * spec; these are the ones LinuxCNC 2.9's hm2_pci.so stores (5i21 8,
 * 5i24 2, 4i69 none). */
static const struct hm2_board_info extra_boards[] = {
    {"5i21", {"P1", "P1"}, 2, 32, "3s400pq208", 8, 1, 1, 48000000, 96000000, 0, NULL, 0},
    {"5i24", {"P4", "P3", "P2"}, 3, 24, "6slx16ftg256", 2, 1, 0, 0, 0, 0, NULL, 0},
    {"4i69-16", {"P1", "P3", "P4"}, 3, 24, "6slx16ftg256", 0, 1, 1, 0, 0, 0, NULL, 0},
    {"4i69-25", {"P1", "P3", "P4"}, 3, 24, "6slx25ftg256", 0, 1, 1, 0, 0, 0, NULL, 0},
};

const struct hm2_pci_id *hm2_pci_match(const struct pci_sysfs_dev *d)
{
    for (size_t i = 0; i < sizeof(ids) / sizeof(ids[0]); i++)
        if (ids[i].vendor == d->vendor && ids[i].device == d->device &&
            ids[i].subsystem_vendor == d->subsystem_vendor &&
            ids[i].subsystem_device == d->subsystem_device)
            return &ids[i];
    return NULL;
}

const struct hm2_board_info *hm2_pci_board_info(const struct hm2_pci_id *id)
{
    const struct hm2_board_info *b = hm2_board_lookup(id->board);
    if (b)
        return b;
    for (size_t i = 0; i < sizeof(extra_boards) / sizeof(extra_boards[0]); i++)
        if (strcasecmp(extra_boards[i].name, id->board) == 0)
            return &extra_boards[i];
    return NULL;
}

int hm2_pci_type_index(const struct hm2_pci_id *const *list, int n, const struct hm2_pci_id *id)
{
    int k = 0;
    for (int i = 0; i < n; i++)
        if (strcmp(list[i]->model, id->model) == 0)
            k++;
    return k;
}

/* Messages go to the board's log sink (hm2_log_printf, hostmot2/msg.c). */
#define blog(board, ...) hm2_log_printf((board)->log, (board)->log_ctx, __VA_ARGS__)

/* ---- the hm2 window: aligned 32-bit accesses only (spec §17.1) ---- */

static int window_check(struct hm2_pci_board *b, uint32_t addr, size_t size)
{
    if (addr % 4 || size % 4 || (size_t)addr + size > HM2_PCI_WINDOW_SIZE || !b->window.mem)
        return -EINVAL;
    return 0;
}

static int pci_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    struct hm2_pci_board *b = llio->priv;
    int r = window_check(b, addr, size);
    if (r)
        return r;
    volatile const uint32_t *src = b->window.mem + addr / 4;
    uint8_t *dst = buffer;
    for (size_t i = 0; i < size / 4; i++) {
        uint32_t v = le32toh(src[i]);
        memcpy(dst + 4 * i, &v, 4);
    }
    return 0;
}

static int pci_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    struct hm2_pci_board *b = llio->priv;
    int r = window_check(b, addr, size);
    if (r)
        return r;
    volatile uint32_t *dst = b->window.mem + addr / 4;
    const uint8_t *src = buffer;
    for (size_t i = 0; i < size / 4; i++) {
        uint32_t v;
        memcpy(&v, src + 4 * i, 4);
        dst[i] = htole32(v);
    }
    return 0;
}

/* ---- PLX register access through the sysfs BARs ---- */

static int sysfs_ctrl_read(void *ctx, uint32_t off, uint32_t *val)
{
    struct hm2_pci_board *b = ctx;
    return pci_bar_read32(&b->ctrl, off, val);
}

static int sysfs_ctrl_write(void *ctx, uint32_t off, uint32_t val)
{
    struct hm2_pci_board *b = ctx;
    return pci_bar_write32(&b->ctrl, off, val);
}

static int sysfs_data_write(void *ctx, uint8_t val)
{
    struct hm2_pci_board *b = ctx;
    return pci_bar_write8(&b->data, 0, val);
}

static const struct hm2_pci_plx_ops sysfs_plx_ops = {sysfs_ctrl_read, sysfs_ctrl_write,
                                                     sysfs_data_write};

static int ctrl_rd(struct hm2_pci_board *b, uint32_t off, uint32_t *val)
{
    int r = b->plx->ctrl_read(b->plx_ctx, off, val);
    if (r)
        blog(b, HM2_ERR, "%s: cannot read PLX register 0x%02X: %s", b->llio.name, off,
             strerror(-r));
    return r;
}

static int ctrl_wr(struct hm2_pci_board *b, uint32_t off, uint32_t val)
{
    int r = b->plx->ctrl_write(b->plx_ctx, off, val);
    if (r)
        blog(b, HM2_ERR, "%s: cannot write PLX register 0x%02X: %s", b->llio.name, off,
             strerror(-r));
    return r;
}

/* Every byte of the 'e' chunk, bit-reversed: the byte port drives the
 * FPGA's D0 with the byte's MSB (spec §18). */
static int send_bitstream(struct hm2_pci_board *b, const struct hm2_bitfile *bf)
{
    for (uint32_t i = 0; i < bf->size; i++) {
        int r = b->plx->data_write(b->plx_ctx, hm2_bitfile_reverse(bf->data[i]));
        if (r) {
            blog(b, HM2_ERR, "%s: writing configuration byte %u of %u failed: %s", b->llio.name,
                 i, bf->size, strerror(-r));
            return r;
        }
    }
    return 0;
}

/* ---- PLX 9030 (spec §17.1) ---- */

static int plx9030_reset(hm2_llio_t *llio)
{
    struct hm2_pci_board *b = llio->priv;
    uint32_t st;
    int r;
    if ((r = ctrl_rd(b, PLX9030_CTRL_STAT, &st)))
        return r;
    uint32_t ctl = (st & ~PLX9030_PROGRAM_N) | PLX9030_WRITE_N | PLX9030_LED_N;
    if ((r = ctrl_wr(b, PLX9030_CTRL_STAT, ctl)) || (r = ctrl_rd(b, PLX9030_CTRL_STAT, &st)))
        return r;
    if (st & (PLX9030_DONE | PLX9030_INIT_N)) {
        blog(b, HM2_ERR, "%s: FPGA did not reset: /INIT = %d, DONE = %d", llio->name,
             (st & PLX9030_INIT_N) ? 1 : 0, (st & PLX9030_DONE) ? 1 : 0);
        return -EIO;
    }
    if ((r = ctrl_wr(b, PLX9030_CTRL_STAT, ctl | PLX9030_PROGRAM_N)))
        return r;
    /* the FPGA clears its configuration memory, then releases /INIT */
    for (int i = 0; i < PLX9030_INIT_POLLS; i++) {
        if ((r = ctrl_rd(b, PLX9030_CTRL_STAT, &st)))
            return r;
        if (st & PLX9030_INIT_N)
            return 0;
    }
    blog(b, HM2_ERR, "%s: FPGA did not come out of /INIT", llio->name);
    return -EIO;
}

static int plx9030_program(hm2_llio_t *llio, const struct hm2_bitfile *bf)
{
    struct hm2_pci_board *b = llio->priv;
    uint32_t st;
    int r;
    if ((r = ctrl_rd(b, PLX9030_CTRL_STAT, &st)))
        return r;
    /* /WRITE low enables the byte port; /LED low lights the LED meanwhile */
    if ((r = ctrl_wr(b, PLX9030_CTRL_STAT, st & ~(PLX9030_WRITE_N | PLX9030_LED_N))))
        return r;
    if ((r = send_bitstream(b, bf)) || (r = ctrl_rd(b, PLX9030_CTRL_STAT, &st)))
        goto fail;
    if (!(st & PLX9030_INIT_N)) {
        blog(b, HM2_ERR, "%s: FPGA asserted /INIT: CRC error", llio->name);
        goto fail;
    }
    if (!(st & PLX9030_DONE)) {
        blog(b, HM2_ERR, "%s: FPGA did not assert DONE", llio->name);
        goto fail;
    }
    return ctrl_wr(b, PLX9030_CTRL_STAT, st | PLX9030_WRITE_N | PLX9030_LED_N);
fail:
    /* leave the FPGA held in reset rather than half configured */
    if (ctrl_rd(b, PLX9030_CTRL_STAT, &st) == 0)
        ctrl_wr(b, PLX9030_CTRL_STAT,
                (st & ~PLX9030_PROGRAM_N) | PLX9030_WRITE_N | PLX9030_LED_N);
    return -EIO;
}

/* The 9030's local-bus regions must end cycles on READY# from the FPGA. */
static int plx9030_fix_lasbrd(struct hm2_pci_board *b)
{
    for (int i = 0; i < 4; i++) {
        uint32_t v;
        int r = ctrl_rd(b, PLX9030_LASBRD(i), &v);
        if (r)
            return r;
        if (v & PLX9030_LASBRD_READY)
            continue;
        blog(b, HM2_INFO, "%s: LAS%dBRD #READY is off, enabling now", b->llio.name, i);
        if ((r = ctrl_wr(b, PLX9030_LASBRD(i), v | PLX9030_LASBRD_READY)))
            return r;
    }
    return 0;
}

/* ---- PLX 9054/9056 (spec §17.1) ---- */

static int plx9054_reset(hm2_llio_t *llio)
{
    struct hm2_pci_board *b = llio->priv;
    uint32_t st;
    int r;
    if ((r = ctrl_rd(b, PLX9054_CTRL_STAT, &st)))
        return r;
    /* the two USER pins become GPIO: /PROGRAM an output, DONE an input */
    uint32_t ctl = st | PLX9054_DONE_ENABLE | PLX9054_PROGRAM_ENABLE;
    if ((r = ctrl_wr(b, PLX9054_CTRL_STAT, ctl)) ||
        (r = ctrl_wr(b, PLX9054_CTRL_STAT, ctl & ~PLX9054_PROGRAM_N)) ||
        (r = ctrl_rd(b, PLX9054_CTRL_STAT, &st)))
        return r;
    if (st & PLX9054_DONE) {
        blog(b, HM2_ERR, "%s: /DONE status bit indicates busy at start of programming",
             llio->name);
        return -EIO;
    }
    if ((r = ctrl_wr(b, PLX9054_CTRL_STAT, ctl | PLX9054_PROGRAM_N)))
        return r;
    /* no /INIT to watch: wait >= 100 us for the configuration clear */
    for (int i = 0; i < PLX9054_RESET_READS; i++)
        if ((r = ctrl_rd(b, PLX9054_CTRL_STAT, &st)))
            return r;
    return 0;
}

static int plx9054_program(hm2_llio_t *llio, const struct hm2_bitfile *bf)
{
    struct hm2_pci_board *b = llio->priv;
    uint32_t st;
    int r = send_bitstream(b, bf);
    if (r)
        return -EIO;
    for (int i = 0; i < PLX9054_DONE_POLLS; i++) {
        if ((r = ctrl_rd(b, PLX9054_CTRL_STAT, &st)))
            return r;
        if (st & PLX9054_DONE)
            return 0;
    }
    blog(b, HM2_ERR, "%s: Error: Not /DONE; programming not completed.", llio->name);
    return -EIO;
}

/* ---- setup ---- */

static int window_bar(const struct hm2_pci_id *id)
{
    switch (id->bridge) {
    case HM2_PCI_PLX9030: return 5;
    case HM2_PCI_PLX9054: return 3;
    default: return 0;
    }
}

static void fill_llio(struct hm2_pci_board *b, const struct hm2_board_info *info, int index)
{
    hm2_board_fill_llio(info, index, &b->llio);
    /* the name follows the PCI table's model ("4i69"), not the table entry */
    snprintf(b->llio.name, sizeof(b->llio.name), "hm2_%s.%d", b->id->model, index);
    b->llio.threadsafe = 1;
    b->llio.read = pci_read;
    b->llio.write = pci_write;
    b->llio.priv = b;
    if (b->id->bridge == HM2_PCI_PLX9030) {
        b->llio.reset = plx9030_reset;
        b->llio.program_fpga = plx9030_program;
    } else if (b->id->bridge == HM2_PCI_PLX9054) {
        b->llio.reset = plx9054_reset;
        b->llio.program_fpga = plx9054_program;
    }
}

static void discovered(struct hm2_pci_board *b)
{
    if (b->id->old_eeprom)
        blog(b, HM2_PRINT,
             "hm2_pci: discovered OLD %s at %s, please consider upgrading your EEPROM",
             b->id->board, b->dev.addr);
    else
        blog(b, HM2_PRINT, "hm2_pci: discovered %s at %s", b->id->board, b->dev.addr);
}

static int open_plx(struct hm2_pci_board *b, const struct hm2_pci_plx_ops *plx, void *plx_ctx)
{
    char err[PCI_SYSFS_PATH_LEN + 128];
    if (plx) {
        b->plx = plx;
        b->plx_ctx = plx_ctx;
        return 0;
    }
    uint32_t ctrl_need = b->id->bridge == HM2_PCI_PLX9030 ? PLX9030_CTRL_STAT + 4
                                                          : PLX9054_CTRL_STAT + 4;
    int r = pci_bar_open(&b->dev, 1, ctrl_need, &b->ctrl, err, sizeof(err));
    if (!r)
        r = pci_bar_open(&b->dev, 2, 1, &b->data, err, sizeof(err));
    if (r) {
        blog(b, HM2_ERR, "%s: cannot open the PLX bridge registers: %s", b->llio.name, err);
        return r;
    }
    b->plx = &sysfs_plx_ops;
    b->plx_ctx = b;
    return 0;
}

int hm2_pci_setup(struct hm2_pci_board *b, const struct pci_sysfs_dev *dev,
                  const struct hm2_pci_id *id, int type_index, const struct hm2_pci_plx_ops *plx,
                  void *plx_ctx, hm2_log_fn log, void *log_ctx)
{
    char err[PCI_SYSFS_PATH_LEN + 128];
    memset(b, 0, sizeof(*b));
    b->window.fd = b->ctrl.fd = b->data.fd = -1;
    b->dev = *dev;
    b->id = id;
    b->log = log;
    b->log_ctx = log_ctx;
    discovered(b);
    const struct hm2_board_info *info = hm2_pci_board_info(id);
    if (!info) { /* only if the id table and the board tables disagree */
        blog(b, HM2_ERR, "hm2_pci: no board facts for %s at %s", id->board, dev->addr);
        return -ENODEV;
    }
    fill_llio(b, info, type_index);
    int r = pci_bar_open(dev, window_bar(id), HM2_PCI_WINDOW_SIZE, &b->window, err, sizeof(err));
    if (r) {
        blog(b, HM2_ERR, "%s: could not map in FPGA address space", b->llio.name);
        blog(b, HM2_ERR, "%s:     %s", b->llio.name, err);
        goto fail;
    }
    if (id->bridge != HM2_PCI_NATIVE && (r = open_plx(b, plx, plx_ctx)))
        goto fail;
    if (id->bridge == HM2_PCI_PLX9030 && (r = plx9030_fix_lasbrd(b)))
        goto fail;
    return 0;
fail:
    hm2_pci_teardown(b);
    return r;
}

void hm2_pci_teardown(struct hm2_pci_board *b)
{
    pci_bar_close(&b->window);
    pci_bar_close(&b->ctrl);
    pci_bar_close(&b->data);
    b->plx = NULL;
}

int hm2_pci_tool_open(struct hm2_pci_tool_board *t, const struct pci_sysfs_dev *dev,
                      int type_index, hm2_log_fn log, void *log_ctx, char *why, size_t whylen)
{
    char err[PCI_SYSFS_PATH_LEN + 64];
    int r = pci_sysfs_enable(dev, &t->was_enabled, err, sizeof(err));
    if (r) {
        snprintf(why, whylen, "cannot enable PCI device %s: %s", dev->addr, err);
        return r;
    }
    r = hm2_pci_setup(&t->board, dev, hm2_pci_match(dev), type_index, NULL, NULL, log, log_ctx);
    if (r) {
        if (!t->was_enabled)
            pci_sysfs_disable(dev);
        snprintf(why, whylen, "cannot map the hm2 window of %s", dev->addr);
    }
    return r;
}

void hm2_pci_tool_close(struct hm2_pci_tool_board *t)
{
    hm2_pci_teardown(&t->board);
    if (!t->was_enabled)
        pci_sysfs_disable(&t->board.dev);
}
