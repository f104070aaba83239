/* SPDX-License-Identifier: GPL-2.0-or-later */
/* TRAM: the register blocks read and written every servo period.  Modules
 * register (addr, words, &pointer) during setup; hm2_tram_allocate() gives
 * each block its slice of one read and one write buffer.  Transfers use the
 * llio's queued interface when it has one (one flush per period). */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "hm2_hal.h"

struct tram_entry {
    uint32_t addr;
    int words;
    uint32_t **buf;
};

struct tram_list {
    struct tram_entry *e;
    int n, cap;
    uint32_t *mem;
};

struct hm2_tram {
    struct tram_list rd, wr;
};

static int list_add(hostmot2_t *hm2, struct tram_list *l, uint32_t addr, uint32_t **buf,
                    int words)
{
    if (words <= 0 || addr >= HM2_ADDR_SPACE || (uint64_t)addr + 4u * (uint64_t)words > HM2_ADDR_SPACE) {
        hm2_msg(hm2, HM2_ERR, "TRAM block at 0x%04X (%d words) is outside the register space",
                addr, words);
        return -EINVAL;
    }
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 16;
        struct tram_entry *e = realloc(l->e, (size_t)cap * sizeof(*e));
        if (!e) {
            hm2_msg(hm2, HM2_ERR, "out of memory registering TRAM block at 0x%04X", addr);
            return -ENOMEM;
        }
        l->e = e;
        l->cap = cap;
    }
    l->e[l->n].addr = addr;
    l->e[l->n].words = words;
    l->e[l->n].buf = buf;
    l->n++;
    *buf = NULL;
    return 0;
}

static struct hm2_tram *tram(hostmot2_t *hm2)
{
    if (!hm2->tram)
        hm2->tram = calloc(1, sizeof(struct hm2_tram));
    return hm2->tram;
}

int hm2_tram_add_read(hostmot2_t *hm2, uint32_t addr, uint32_t **buf, int words)
{
    struct hm2_tram *t = tram(hm2);
    return t ? list_add(hm2, &t->rd, addr, buf, words) : -ENOMEM;
}

int hm2_tram_add_write(hostmot2_t *hm2, uint32_t addr, uint32_t **buf, int words)
{
    struct hm2_tram *t = tram(hm2);
    return t ? list_add(hm2, &t->wr, addr, buf, words) : -ENOMEM;
}

static int list_alloc(struct tram_list *l)
{
    int total = 0;
    for (int i = 0; i < l->n; i++)
        total += l->e[i].words;
    l->mem = calloc((size_t)(total ? total : 1), sizeof(uint32_t));
    if (!l->mem)
        return -ENOMEM;
    int off = 0;
    for (int i = 0; i < l->n; i++) {
        *l->e[i].buf = l->mem + off;
        off += l->e[i].words;
    }
    return 0;
}

int hm2_tram_allocate(hostmot2_t *hm2)
{
    struct hm2_tram *t = tram(hm2);
    if (!t || list_alloc(&t->rd) || list_alloc(&t->wr)) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating TRAM buffers");
        return -ENOMEM;
    }
    return 0;
}

static int queue_reads(hostmot2_t *hm2)
{
    hm2_llio_t *llio = hm2->llio;
    struct tram_list *l = &hm2->tram->rd;
    int r = 0;
    for (int i = 0; i < l->n && !r; i++) {
        size_t size = 4u * (size_t)l->e[i].words;
        if (llio->queue_read)
            r = llio->queue_read(llio, l->e[i].addr, *l->e[i].buf, size);
        else
            r = llio->read(llio, l->e[i].addr, *l->e[i].buf, size);
        if (r)
            hm2_msg(hm2, HM2_ERR, "error reading %d words at 0x%04X: %s", l->e[i].words,
                    l->e[i].addr, strerror(-r));
    }
    return r;
}

int hm2_tram_read(hostmot2_t *hm2)
{
    hm2_llio_t *llio = hm2->llio;
    int r = queue_reads(hm2);
    if (!r && llio->send_queued_reads) {
        r = llio->send_queued_reads(llio);
        if (r)
            hm2_msg(hm2, HM2_ERR, "error flushing queued reads: %s", strerror(-r));
    }
    return r;
}

int hm2_tram_read_request(hostmot2_t *hm2)
{
    hm2_llio_t *llio = hm2->llio;
    int r = queue_reads(hm2);
    if (!r) {
        r = llio->request_queued_reads(llio);
        if (r)
            hm2_msg(hm2, HM2_ERR, "error sending the read request: %s", strerror(-r));
    }
    return r;
}

int hm2_tram_read_receive(hostmot2_t *hm2)
{
    int r = hm2->llio->receive_queued_reads(hm2->llio);
    if (r)
        hm2_msg(hm2, HM2_ERR, "error receiving the requested reads: %s", strerror(-r));
    return r;
}

int hm2_tram_write(hostmot2_t *hm2)
{
    hm2_llio_t *llio = hm2->llio;
    struct tram_list *l = &hm2->tram->wr;
    int r = 0;
    for (int i = 0; i < l->n && !r; i++) {
        size_t size = 4u * (size_t)l->e[i].words;
        if (llio->queue_write)
            r = llio->queue_write(llio, l->e[i].addr, *l->e[i].buf, size);
        else
            r = llio->write(llio, l->e[i].addr, *l->e[i].buf, size);
        if (r)
            hm2_msg(hm2, HM2_ERR, "error writing %d words at 0x%04X: %s", l->e[i].words,
                    l->e[i].addr, strerror(-r));
    }
    if (!r && llio->send_queued_writes) {
        r = llio->send_queued_writes(llio);
        if (r)
            hm2_msg(hm2, HM2_ERR, "error flushing queued writes: %s", strerror(-r));
    }
    return r;
}

void hm2_tram_free(hostmot2_t *hm2)
{
    struct hm2_tram *t = hm2->tram;
    if (!t)
        return;
    free(t->rd.e);
    free(t->rd.mem);
    free(t->wr.e);
    free(t->wr.mem);
    free(t);
    hm2->tram = NULL;
}
