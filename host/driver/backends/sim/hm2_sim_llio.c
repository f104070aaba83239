/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2_sim_llio.c - see hm2_sim_llio.h and docs/hm2_sim.md. */
#define _GNU_SOURCE
#include "hm2_sim_llio.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/bitfile.h"

static struct hm2_sim_board *board_of(hm2_llio_t *llio)
{
    return (struct hm2_sim_board *)llio->priv;
}

/* Messages go to the board's log sink (hm2_log_printf, hostmot2/msg.c). */
#define logf_(board, ...) hm2_log_printf((board)->log, (board)->log_ctx, __VA_ARGS__)

static int64_t host_time(struct hm2_sim_board *sb)
{
    return sb->now ? sb->now() : 0;
}

/* After vbc_send failed: a transport failure closes the connection (the
 * board is gone for good: say so once, then fail fast); a board-side error
 * keeps it and is reported every time (the core stops calling after one). */
static int failed(struct hm2_sim_board *sb, int rc, const char *what)
{
    if (sb->vbc.fd < 0) {
        if (!sb->dead)
            logf_(sb, HM2_ERR, "%s: %s failed: %s; the board is gone, every further access "
                               "fails with ENODEV", sb->llio.name, what, sb->vbc.err);
        sb->dead = 1;
        return -ENODEV;
    }
    logf_(sb, HM2_ERR, "%s: %s failed: %s", sb->llio.name, what, sb->vbc.err);
    return rc;
}

static int check_xfer(struct hm2_sim_board *sb, uint32_t addr, size_t size, const char *op)
{
    if ((addr & 3u) || (size & 3u) || size == 0 || addr > 0xFFFFu || size > 0x10000u) {
        logf_(sb, HM2_ERR, "%s: %s of %zu bytes at 0x%04X refused: address and size must be "
                           "non-zero multiples of 4 inside the 64 KiB hm2 window",
              sb->llio.name, op, size, addr);
        return -EINVAL;
    }
    return 0;
}

/* ---- direct access: one round trip each ---- */

static int sim_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    struct hm2_sim_board *sb = board_of(llio);
    int r = check_xfer(sb, addr, size, "read");
    if (r)
        return r;
    if (sb->dead)
        return -ENODEV;
    struct vb_xfer x = {addr, (uint32_t)size};
    pthread_mutex_lock(&sb->lock);
    r = vbc_call(&sb->vbc, VB_READ, (uint64_t)host_time(sb), &x, sizeof(x));
    sb->round_trips++;
    if (r == 0 && sb->vbc.rx_len != size) {
        snprintf(sb->vbc.err, sizeof(sb->vbc.err), "reply has %zu bytes, expected %zu",
                 sb->vbc.rx_len, size);
        r = -EPROTO;
    }
    if (r == 0)
        memcpy(buffer, sb->vbc.rx, size);
    pthread_mutex_unlock(&sb->lock);
    if (r) {
        char what[64];
        snprintf(what, sizeof(what), "read of %zu bytes at 0x%04X", size, addr);
        return failed(sb, r, what);
    }
    return 0;
}

static int sim_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    struct hm2_sim_board *sb = board_of(llio);
    int r = check_xfer(sb, addr, size, "write");
    if (r)
        return r;
    if (sb->dead)
        return -ENODEV;
    struct vb_xfer x = {addr, (uint32_t)size};
    pthread_mutex_lock(&sb->lock);
    vbc_req_start(&sb->vbc);
    r = vbc_req_put(&sb->vbc, &x, sizeof(x));
    if (!r)
        r = vbc_req_put(&sb->vbc, buffer, size);
    if (!r)
        r = vbc_send(&sb->vbc, VB_WRITE, (uint64_t)host_time(sb));
    sb->round_trips++;
    pthread_mutex_unlock(&sb->lock);
    if (r) {
        char what[64];
        snprintf(what, sizeof(what), "write of %zu bytes at 0x%04X", size, addr);
        return failed(sb, r, what);
    }
    return 0;
}

/* ---- queued access: one round trip per flush ---- */

static int queue_grow(struct hm2_sim_board *sb)
{
    struct hm2_sim_queue *q = &sb->q;
    if (q->n < q->cap)
        return 0;
    int cap = q->cap ? q->cap * 2 : 64;
    struct vb_xfer *x = realloc(q->xfer, (size_t)cap * sizeof(*x));
    if (!x)
        goto nomem;
    q->xfer = x;
    void **d = realloc(q->dest, (size_t)cap * sizeof(*d));
    if (!d)
        goto nomem;
    q->dest = d;
    q->cap = cap;
    return 0;
nomem:
    logf_(sb, HM2_ERR, "%s: out of memory for %d queued reads", sb->llio.name, cap);
    return -ENOMEM;
}

static int sim_queue_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    struct hm2_sim_board *sb = board_of(llio);
    int r = check_xfer(sb, addr, size, "queued read");
    if (r || (r = queue_grow(sb)))
        return r;
    struct hm2_sim_queue *q = &sb->q;
    q->xfer[q->n] = (struct vb_xfer){addr, (uint32_t)size};
    q->dest[q->n] = buffer;
    q->n++;
    q->bytes += size;
    return 0;
}

static int sim_send_queued_reads(hm2_llio_t *llio)
{
    struct hm2_sim_board *sb = board_of(llio);
    struct hm2_sim_queue *q = &sb->q;
    int n = q->n;
    size_t bytes = q->bytes;
    q->n = 0;
    q->bytes = 0;
    if (n == 0)
        return 0;
    if (sb->dead)
        return -ENODEV;
    pthread_mutex_lock(&sb->lock);
    int r = vbc_call(&sb->vbc, VB_READ, (uint64_t)host_time(sb), q->xfer,
                     (size_t)n * sizeof(*q->xfer));
    sb->round_trips++;
    if (r == 0 && sb->vbc.rx_len != bytes) {
        snprintf(sb->vbc.err, sizeof(sb->vbc.err), "reply has %zu bytes, expected %zu",
                 sb->vbc.rx_len, bytes);
        r = -EPROTO;
    }
    if (r == 0) {
        const uint8_t *p = sb->vbc.rx;
        for (int i = 0; i < n; i++) {
            memcpy(q->dest[i], p, q->xfer[i].size);
            p += q->xfer[i].size;
        }
    }
    pthread_mutex_unlock(&sb->lock);
    if (r) {
        char what[64];
        snprintf(what, sizeof(what), "queued read of %d transfers", n);
        return failed(sb, r, what);
    }
    return 0;
}

static int sim_queue_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    struct hm2_sim_board *sb = board_of(llio);
    struct hm2_sim_queue *q = &sb->q;
    int r = check_xfer(sb, addr, size, "queued write");
    if (r)
        return r;
    size_t need = q->wlen + sizeof(struct vb_xfer) + size;
    if (need > q->wcap) {
        size_t cap = q->wcap ? q->wcap : 4096;
        while (cap < need)
            cap *= 2;
        uint8_t *p = realloc(q->wbuf, cap);
        if (!p) {
            logf_(sb, HM2_ERR, "%s: out of memory for %zu bytes of queued writes",
                  sb->llio.name, need);
            return -ENOMEM;
        }
        q->wbuf = p;
        q->wcap = cap;
    }
    struct vb_xfer x = {addr, (uint32_t)size};
    memcpy(q->wbuf + q->wlen, &x, sizeof(x));
    memcpy(q->wbuf + q->wlen + sizeof(x), buffer, size);
    q->wlen = need;
    return 0;
}

static int sim_send_queued_writes(hm2_llio_t *llio)
{
    struct hm2_sim_board *sb = board_of(llio);
    struct hm2_sim_queue *q = &sb->q;
    size_t len = q->wlen;
    q->wlen = 0;
    if (len == 0)
        return 0;
    if (sb->dead)
        return -ENODEV;
    pthread_mutex_lock(&sb->lock);
    int r;
    if (sb->async_writes) {
        vbc_req_start(&sb->vbc);
        r = vbc_req_put(&sb->vbc, q->wbuf, len);
        if (!r)
            r = vbc_post(&sb->vbc, VB_WRITE, (uint64_t)host_time(sb));
    } else {
        r = vbc_call(&sb->vbc, VB_WRITE, (uint64_t)host_time(sb), q->wbuf, len);
    }
    sb->round_trips++;
    pthread_mutex_unlock(&sb->lock);
    if (r) {
        char what[64];
        snprintf(what, sizeof(what), "queued write of %zu bytes", len);
        return failed(sb, r, what);
    }
    return 0;
}

/* ---- board time ---- */

static int sim_delay(hm2_llio_t *llio, long ns)
{
    struct hm2_sim_board *sb = board_of(llio);
    if (sb->dead)
        return -ENODEV;
    if (ns <= 0)
        return 0;
    struct vb_time t = {VB_TIME_ADVANCE, 0, (uint64_t)ns};
    pthread_mutex_lock(&sb->lock);
    int r = vbc_call(&sb->vbc, VB_TIME, 0, &t, sizeof(t));
    pthread_mutex_unlock(&sb->lock);
    return r ? failed(sb, r, "board time advance") : 0;
}

/* ---- configuration port ---- */

static int config_call(struct hm2_sim_board *sb, uint32_t op, const uint8_t *bits, uint32_t n,
                       struct vb_config_status *st)
{
    if (sb->dead)
        return -ENODEV;
    struct vb_config c = {op, 0};
    pthread_mutex_lock(&sb->lock);
    vbc_req_start(&sb->vbc);
    int r = vbc_req_put(&sb->vbc, &c, sizeof(c));
    if (!r && n)
        r = vbc_req_put(&sb->vbc, bits, n);
    if (!r)
        r = vbc_send(&sb->vbc, VB_CONFIG, (uint64_t)host_time(sb));
    if (r == 0 && sb->vbc.rx_len < sizeof(*st)) {
        snprintf(sb->vbc.err, sizeof(sb->vbc.err), "short configuration status (%zu bytes)",
                 sb->vbc.rx_len);
        r = -EPROTO;
    }
    if (r == 0)
        memcpy(st, sb->vbc.rx, sizeof(*st));
    pthread_mutex_unlock(&sb->lock);
    return r;
}

static int sim_reset(hm2_llio_t *llio)
{
    struct hm2_sim_board *sb = board_of(llio);
    struct vb_config_status st;
    int r = config_call(sb, VB_CONFIG_RESET, NULL, 0, &st);
    if (r)
        return failed(sb, r, "FPGA reset");
    if (st.done || !st.init) {
        logf_(sb, HM2_ERR, "%s: FPGA did not reset: DONE is %s and /INIT is %s after the "
                           "reset (want DONE low, /INIT high)",
              sb->llio.name, st.done ? "high" : "low", st.init ? "high" : "low");
        return -EIO;
    }
    sb->hello.state = VB_STATE_BLANK;
    return 0;
}

static int sim_program_fpga(hm2_llio_t *llio, const struct hm2_bitfile *bf)
{
    struct hm2_sim_board *sb = board_of(llio);
    struct vb_config_status st;
    int r = config_call(sb, VB_CONFIG_PROGRAM, bf->data, bf->size, &st);
    if (r) {
        if (sb->vbc.fd >= 0) {
            logf_(sb, HM2_ERR, "%s: the board refused the %u-byte bitstream: %s",
                  sb->llio.name, bf->size, sb->vbc.err);
            return -EIO;
        }
        return failed(sb, r, "FPGA programming");
    }
    if (!st.done || !st.init) {
        logf_(sb, HM2_ERR, "%s: FPGA programming failed: DONE is %s and /INIT is %s after "
                           "sending %u bytes (want both high)",
              sb->llio.name, st.done ? "high" : "low", st.init ? "high" : "low", bf->size);
        return -EIO;
    }
    snprintf(sb->hello.firmware, sizeof(sb->hello.firmware), "%.*s",
             (int)sizeof(st.firmware), st.firmware);
    sb->hello.state = VB_STATE_CONFIGURED;
    logf_(sb, HM2_INFO, "%s: board programmed with %s (%u bytes), DONE high", sb->llio.name,
          sb->hello.firmware, bf->size);
    return 0;
}

/* ---- setup ---- */

static int check_hello(struct hm2_sim_board *sb, const char *path, const char *board)
{
    struct vb_hello *h = &sb->hello;
    h->board[sizeof(h->board) - 1] = 0;
    h->firmware[sizeof(h->firmware) - 1] = 0;
    h->fpga_part[sizeof(h->fpga_part) - 1] = 0;
    if (h->version != VB_PROTO_VERSION) {
        logf_(sb, HM2_ERR, "hm2_sim: virtual board at %s speaks protocol version %u, this "
                           "driver version %u", path, h->version, VB_PROTO_VERSION);
        return -EPROTO;
    }
    if (h->bus != VB_BUS_LOCAL) {
        logf_(sb, HM2_ERR, "hm2_sim: virtual board at %s is a %s, not a local-bus (PCI-style) "
                           "board; EPP boards are driven by hm2_7i43 port=sim:%s",
              path, h->board, path);
        return -ENODEV;
    }
    if (board && *board && strcasecmp(board, h->board) != 0) {
        logf_(sb, HM2_ERR, "hm2_sim: virtual board at %s is a %s, but board=%s was given", path,
              h->board, board);
        return -ENODEV;
    }
    sb->info = hm2_board_lookup(h->board);
    if (!sb->info) {
        logf_(sb, HM2_ERR, "hm2_sim: virtual board at %s is a '%s', which is not in the board "
                           "table", path, h->board);
        return -ENODEV;
    }
    return 0;
}

int hm2_sim_setup(struct hm2_sim_board *sb, const char *path, const char *board, int index,
                  hm2_sim_now_fn now, hm2_log_fn log, void *log_ctx)
{
    memset(sb, 0, sizeof(*sb));
    sb->vbc.fd = -1;
    sb->now = now;
    sb->log = log;
    sb->log_ctx = log_ctx;
    if (pthread_mutex_init(&sb->lock, NULL)) {
        logf_(sb, HM2_ERR, "hm2_sim: cannot create the lock of the board at %s", path);
        return -ENOMEM;
    }
    sb->lock_ok = 1;
    int r = vbc_open(&sb->vbc, path);
    if (r) {
        logf_(sb, HM2_ERR, "hm2_sim: %s (is bin/vboard running?)", sb->vbc.err);
        goto fail;
    }
    r = vbc_hello(&sb->vbc, &sb->hello);
    if (r) {
        logf_(sb, HM2_ERR, "hm2_sim: HELLO failed: %s", sb->vbc.err);
        goto fail;
    }
    if ((r = check_hello(sb, path, board)))
        goto fail;
    hm2_llio_t *l = &sb->llio;
    hm2_board_fill_llio(sb->info, index, l);
    l->priv = sb;
    l->read = sim_read;
    l->write = sim_write;
    l->queue_read = sim_queue_read;
    l->send_queued_reads = sim_send_queued_reads;
    l->queue_write = sim_queue_write;
    l->send_queued_writes = sim_send_queued_writes;
    l->delay = sim_delay;
    if (sb->info->programmable) {
        l->reset = sim_reset;
        l->program_fpga = sim_program_fpga;
    }
    return 0;
fail:
    hm2_sim_teardown(sb);
    return r;
}

void hm2_sim_teardown(struct hm2_sim_board *sb)
{
    vbc_close(&sb->vbc);
    if (sb->dead && vbc_remove_stale(sb->vbc.path))
        logf_(sb, HM2_PRINT, "hm2_sim: removed the socket %s left by the dead board",
              sb->vbc.path);
    free(sb->q.xfer);
    free(sb->q.dest);
    free(sb->q.wbuf);
    sb->q = (struct hm2_sim_queue){0};
    if (sb->lock_ok)
        pthread_mutex_destroy(&sb->lock);
    sb->lock_ok = 0;
}
