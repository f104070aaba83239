/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Register-image llio backend (see llio_image.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/bitfile.h"
#include "hm2/llio_image.h"

static struct hm2_image_llio *IM(hm2_llio_t *l)
{
    return (struct hm2_image_llio *)l->priv;
}

static int range_ok(uint32_t addr, size_t size)
{
    return addr < HM2_IMAGE_SIZE && size <= HM2_IMAGE_SIZE - addr && !(addr & 3) && !(size & 3);
}

static int im_read(hm2_llio_t *l, uint32_t addr, void *buf, size_t size)
{
    struct hm2_image_llio *im = IM(l);
    if (!range_ok(addr, size))
        return -EINVAL;
    im->reads++;
    if (im->fail_lo >= 0 && (int64_t)addr <= im->fail_hi &&
        (int64_t)addr + (int64_t)size - 1 >= im->fail_lo)
        return -EIO;
    uint32_t *w = buf;
    for (size_t i = 0; i < size / 4; i++)
        w[i] = hm2_image_get32(im, addr + 4u * (uint32_t)i);
    return 0;
}

static int im_write(hm2_llio_t *l, uint32_t addr, const void *buf, size_t size)
{
    struct hm2_image_llio *im = IM(l);
    if (!range_ok(addr, size))
        return -EINVAL;
    im->writes++;
    const uint32_t *w = buf;
    for (size_t i = 0; i < size / 4; i++) {
        uint32_t a = addr + 4u * (uint32_t)i;
        if (!im->discard_writes)
            hm2_image_put32(im, a, w[i]);
        if (im->on_write)
            im->on_write(im, a, w[i]);
    }
    return 0;
}

static int im_queue_read(hm2_llio_t *l, uint32_t addr, void *buf, size_t size)
{
    struct hm2_image_llio *im = IM(l);
    if (!range_ok(addr, size) || im->nrq >= HM2_IMAGE_MAX_QUEUE) {
        im->nrq = 0; /* contract: a failed queue call discards the queue */
        return range_ok(addr, size) ? -ENOSPC : -EINVAL;
    }
    im->rq[im->nrq].addr = addr;
    im->rq[im->nrq].buf = buf;
    im->rq[im->nrq].size = size;
    im->nrq++;
    return 0;
}

static int im_send_queued_reads(hm2_llio_t *l)
{
    struct hm2_image_llio *im = IM(l);
    int r = 0;
    im->flushes++;
    for (int i = 0; i < im->nrq && !r; i++)
        r = im_read(l, im->rq[i].addr, im->rq[i].buf, im->rq[i].size);
    im->nrq = 0;
    return r;
}

static int im_queue_write(hm2_llio_t *l, uint32_t addr, const void *buf, size_t size)
{
    struct hm2_image_llio *im = IM(l);
    int r = 0;
    /* large writes are split into queue entries of 64 bytes */
    while (size && !r) {
        size_t n = size > sizeof(im->wq[0].data) ? sizeof(im->wq[0].data) : size;
        if (!range_ok(addr, n) || im->nwq >= HM2_IMAGE_MAX_QUEUE) {
            im->nwq = 0; /* contract: a failed queue call discards the queue */
            return range_ok(addr, n) ? -ENOSPC : -EINVAL;
        }
        im->wq[im->nwq].addr = addr;
        memcpy(im->wq[im->nwq].data, buf, n);
        im->wq[im->nwq].size = n;
        im->nwq++;
        addr += (uint32_t)n;
        buf = (const uint8_t *)buf + n;
        size -= n;
    }
    return r;
}

static int im_send_queued_writes(hm2_llio_t *l)
{
    struct hm2_image_llio *im = IM(l);
    int r = 0;
    im->flushes++;
    for (int i = 0; i < im->nwq && !r; i++)
        r = im_write(l, im->wq[i].addr, im->wq[i].data, im->wq[i].size);
    im->nwq = 0;
    return r;
}

void hm2_image_llio_init(struct hm2_image_llio *im, const char *name)
{
    memset(im, 0, sizeof(*im));
    snprintf(im->llio.name, sizeof(im->llio.name), "%s", name);
    im->llio.read = im_read;
    im->llio.write = im_write;
    im->llio.priv = im;
    im->llio.fpga_part_number = "";
    im->fail_lo = -1;
    im->fail_hi = -1;
}

void hm2_image_llio_set_board(struct hm2_image_llio *im, const struct hm2_board_info *b, int index)
{
    hm2_board_fill_llio(b, index, &im->llio);
}

void hm2_image_llio_set_queued(struct hm2_image_llio *im, int on)
{
    im->llio.queue_read = on ? im_queue_read : NULL;
    im->llio.send_queued_reads = on ? im_send_queued_reads : NULL;
    im->llio.queue_write = on ? im_queue_write : NULL;
    im->llio.send_queued_writes = on ? im_send_queued_writes : NULL;
}

static void synthesize_id_block(struct hm2_image_llio *im)
{
    hm2_image_put32(im, 0x100, 0x55AACAFEu);
    hm2_image_put32(im, 0x104, 0x54534F48u); /* "HOST" */
    hm2_image_put32(im, 0x108, 0x32544F4Du); /* "MOT2" */
    hm2_image_put32(im, 0x10C, 0x400u);
}

/* Lines of 1..8 hex digits; returns the word count, or -1 if the file is
 * not in that form. */
static int parse_hex_words(const uint8_t *buf, size_t len, uint32_t *words, int max)
{
    int n = 0;
    size_t i = 0;
    while (i < len) {
        uint32_t w = 0;
        int digits = 0;
        while (i < len && buf[i] != '\n' && buf[i] != '\r') {
            int c = buf[i], v;
            if (c >= '0' && c <= '9') v = c - '0';
            else if (c >= 'a' && c <= 'f') v = c - 'a' + 10;
            else if (c >= 'A' && c <= 'F') v = c - 'A' + 10;
            else return -1;
            if (++digits > 8)
                return -1;
            w = w << 4 | (uint32_t)v;
            i++;
        }
        while (i < len && (buf[i] == '\n' || buf[i] == '\r'))
            i++;
        if (digits == 0)
            continue;
        if (n >= max)
            return -1;
        words[n++] = w;
    }
    return n;
}

int hm2_image_llio_load(struct hm2_image_llio *im, const char *path, char *err, size_t errlen)
{
    uint8_t *buf;
    size_t len;
    int r = hm2_read_file(path, HM2_IMAGE_SIZE, &buf, &len);
    if (r) {
        snprintf(err, errlen, "cannot read image %s: %s", path,
                 r == -EFBIG ? "larger than 64 KiB" : strerror(-r));
        return r;
    }
    uint32_t words[256];
    int nwords = parse_hex_words(buf, len, words, 256);
    if (nwords > 0) {
        /* hm2gen's .idrom.hex: one 32-bit IDROM word per line */
        memset(im->mem, 0, sizeof(im->mem));
        for (int i = 0; i < nwords; i++)
            hm2_image_put32(im, 0x400u + 4u * (uint32_t)i, words[i]);
        synthesize_id_block(im);
    } else if (len == HM2_IMAGE_SIZE) {
        memcpy(im->mem, buf, len);
    } else if (len == 1024) {
        memset(im->mem, 0, sizeof(im->mem));
        memcpy(im->mem + 0x400, buf, len);
        synthesize_id_block(im);
    } else {
        snprintf(err, errlen,
                 "image %s is %zu bytes; expected 65536 (register space), 1024 (IDROM) or an "
                 "IDROM hex file (one 32-bit word per line, at most 256)",
                 path,
                 len);
        r = -EINVAL;
    }
    free(buf);
    return r;
}
