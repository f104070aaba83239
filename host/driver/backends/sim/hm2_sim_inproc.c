/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2_sim_inproc.c - see hm2_sim_inproc.h and docs/hm2_sim.md. */
#define _GNU_SOURCE
#include "hm2_sim_inproc.h"

#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "hm2/bitfile.h"

/* Messages go to the board's log sink (hm2_log_printf, hostmot2/msg.c). */
#define IB_LOG(ib, level, ...) hm2_log_printf((ib)->log, (ib)->log_ctx, level, __VA_ARGS__)

/* ---- the library ---- */

/* lib/libvboard_inproc.so beside lib/rtlib/ where this code was loaded from */
static int default_path(char *out, size_t len)
{
    Dl_info di;
    if (!dladdr((void *)default_path, &di) || !di.dli_fname)
        return -ENOENT;
    char dir[512];
    snprintf(dir, sizeof(dir), "%s", di.dli_fname);
    for (int up = 0; up < 2; up++) {
        char *slash = strrchr(dir, '/');
        if (!slash)
            return -ENOENT;
        *slash = 0;
    }
    int n = snprintf(out, len, "%s/%s", dir, VBI_LIBRARY);
    return n < 0 || (size_t)n >= len ? -ENAMETOOLONG : 0;
}

int hm2_sim_inproc_lib_open(struct hm2_sim_inproc_lib *lib, const char *path, hm2_log_fn log,
                            void *log_ctx)
{
    memset(lib, 0, sizeof(*lib));
    const char *env = getenv("HM2_SIM_INPROC_LIB");
    if (path && *path)
        snprintf(lib->path, sizeof(lib->path), "%s", path);
    else if (env && *env)
        snprintf(lib->path, sizeof(lib->path), "%s", env);
    else if (default_path(lib->path, sizeof(lib->path))) {
        hm2_log_printf(log, log_ctx, HM2_ERR,
                       "hm2_sim: cannot tell where the module was loaded from to find %s; set "
                       "HM2_SIM_INPROC_LIB",
                       VBI_LIBRARY);
        return -ENOENT;
    }
    lib->dl = dlopen(lib->path, RTLD_NOW | RTLD_LOCAL);
    if (!lib->dl) {
        hm2_log_printf(log, log_ctx, HM2_ERR,
                       "hm2_sim: inproc=1: cannot load the in-process board library %s: %s "
                       "(built by `make build` as lib/%s)",
                       lib->path, dlerror(), VBI_LIBRARY);
        return -ENOENT;
    }
    vbi_get_api_fn get = (vbi_get_api_fn)dlsym(lib->dl, VBI_ENTRY);
    const vbi_api_t *api = get ? get() : NULL;
    if (!api || api->abi != VBI_ABI) {
        hm2_log_printf(log, log_ctx, HM2_ERR,
                       "hm2_sim: inproc=1: %s is not an in-process board library of this build "
                       "(%s; want ABI %u)",
                       lib->path, !get ? "no " VBI_ENTRY : !api ? "no function table" : "other ABI",
                       VBI_ABI);
        dlclose(lib->dl);
        lib->dl = NULL;
        return -ENOEXEC;
    }
    lib->api = api;
    return 0;
}

void hm2_sim_inproc_lib_close(struct hm2_sim_inproc_lib *lib)
{
    if (lib->dl)
        dlclose(lib->dl);
    memset(lib, 0, sizeof(*lib));
}

/* ---- llio ---- */

static struct hm2_sim_inproc *ib_of(hm2_llio_t *llio)
{
    return (struct hm2_sim_inproc *)llio->priv;
}

static uint64_t host_time(struct hm2_sim_inproc *ib)
{
    return ib->now ? (uint64_t)ib->now() : 0;
}

static uint64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Time of one flush call, and the library's counters around it (stats=1). */
struct flush_meter {
    struct vbi_stats st;
    uint64_t t0;
};

static void meter_start(struct hm2_sim_inproc *ib, struct flush_meter *m)
{
    if (!ib->stats)
        return;
    ib->api->stats(ib->vb, &m->st);
    m->t0 = mono_ns();
}

static void meter_stop(struct hm2_sim_inproc *ib, struct flush_meter *m)
{
    if (!ib->stats)
        return;
    uint64_t t1 = mono_ns();
    struct vbi_stats st;
    ib->api->stats(ib->vb, &st);
    ib->flush_ns += t1 - m->t0;
    ib->model_ns += st.board_ns - m->st.board_ns;
    ib->words_read += st.read_words - m->st.read_words;
    ib->words_written += st.write_words - m->st.write_words;
}

static int check_xfer(struct hm2_sim_inproc *ib, uint32_t addr, size_t size, const char *op)
{
    if ((addr & 3u) || (size & 3u) || size == 0 || addr > 0xFFFFu || size > 0x10000u) {
        IB_LOG(ib, HM2_ERR, "%s: %s of %zu bytes at 0x%04X refused: address and size must be "
                            "non-zero multiples of 4 inside the 64 KiB hm2 window",
               ib->llio.name, op, size, addr);
        return -EINVAL;
    }
    return 0;
}

static int failed(struct hm2_sim_inproc *ib, int rc, const char *what)
{
    IB_LOG(ib, HM2_ERR, "%s: %s failed: %s", ib->llio.name, what, ib->api->error(ib->vb));
    return rc;
}

static int ip_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    struct hm2_sim_inproc *ib = ib_of(llio);
    int r = check_xfer(ib, addr, size, "read");
    if (r)
        return r;
    struct vb_xfer x = {addr, (uint32_t)size};
    pthread_mutex_lock(&ib->lock);
    r = ib->api->read(ib->vb, host_time(ib), &x, &buffer, 1);
    pthread_mutex_unlock(&ib->lock);
    if (r) {
        char what[64];
        snprintf(what, sizeof(what), "read of %zu bytes at 0x%04X", size, addr);
        return failed(ib, r, what);
    }
    return 0;
}

static int ip_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    struct hm2_sim_inproc *ib = ib_of(llio);
    int r = check_xfer(ib, addr, size, "write");
    if (r)
        return r;
    struct vb_xfer x = {addr, (uint32_t)size};
    pthread_mutex_lock(&ib->lock);
    r = ib->api->write(ib->vb, host_time(ib), &x, &buffer, 1);
    pthread_mutex_unlock(&ib->lock);
    if (r) {
        char what[64];
        snprintf(what, sizeof(what), "write of %zu bytes at 0x%04X", size, addr);
        return failed(ib, r, what);
    }
    return 0;
}

static int grow(struct hm2_sim_inproc *ib, void **p, int cap, size_t each)
{
    void *n = realloc(*p, (size_t)cap * each);
    if (!n) {
        IB_LOG(ib, HM2_ERR, "%s: out of memory for %d queued transfers", ib->llio.name, cap);
        return -ENOMEM;
    }
    *p = n;
    return 0;
}

static int ip_queue_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    struct hm2_sim_inproc *ib = ib_of(llio);
    int r = check_xfer(ib, addr, size, "queued read");
    if (r)
        return r;
    if (ib->rn == ib->rcap) {
        int cap = ib->rcap ? ib->rcap * 2 : 64;
        if ((r = grow(ib, (void **)&ib->rx, cap, sizeof(*ib->rx))) ||
            (r = grow(ib, (void **)&ib->rdest, cap, sizeof(*ib->rdest))))
            return r;
        ib->rcap = cap;
    }
    ib->rx[ib->rn] = (struct vb_xfer){addr, (uint32_t)size};
    ib->rdest[ib->rn] = buffer;
    ib->rn++;
    return 0;
}

static int ip_send_queued_reads(hm2_llio_t *llio)
{
    struct hm2_sim_inproc *ib = ib_of(llio);
    int n = ib->rn;
    ib->rn = 0;
    if (n == 0)
        return 0;
    pthread_mutex_lock(&ib->lock);
    struct flush_meter m;
    meter_start(ib, &m);
    int r = ib->api->read(ib->vb, host_time(ib), ib->rx, ib->rdest, (size_t)n);
    meter_stop(ib, &m);
    ib->read_flushes++;
    pthread_mutex_unlock(&ib->lock);
    if (r) {
        char what[64];
        snprintf(what, sizeof(what), "queued read of %d transfers", n);
        return failed(ib, r, what);
    }
    return 0;
}

/* The data is copied now: the caller's buffer may change before the flush. */
static int ip_queue_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    struct hm2_sim_inproc *ib = ib_of(llio);
    int r = check_xfer(ib, addr, size, "queued write");
    if (r)
        return r;
    if (ib->wn == ib->wcap) {
        int cap = ib->wcap ? ib->wcap * 2 : 64;
        if ((r = grow(ib, (void **)&ib->wx, cap, sizeof(*ib->wx))) ||
            (r = grow(ib, (void **)&ib->woff, cap, sizeof(*ib->woff))) ||
            (r = grow(ib, (void **)&ib->wsrc, cap, sizeof(*ib->wsrc))))
            return r;
        ib->wcap = cap;
    }
    if (ib->wlen + size > ib->wbcap) {
        size_t cap = ib->wbcap ? ib->wbcap : 4096;
        while (cap < ib->wlen + size)
            cap *= 2;
        uint8_t *p = realloc(ib->wbuf, cap);
        if (!p) {
            IB_LOG(ib, HM2_ERR, "%s: out of memory for %zu bytes of queued writes",
                   ib->llio.name, cap);
            return -ENOMEM;
        }
        ib->wbuf = p;
        ib->wbcap = cap;
    }
    memcpy(ib->wbuf + ib->wlen, buffer, size);
    ib->wx[ib->wn] = (struct vb_xfer){addr, (uint32_t)size};
    ib->woff[ib->wn] = ib->wlen;
    ib->wn++;
    ib->wlen += size;
    return 0;
}

static int ip_send_queued_writes(hm2_llio_t *llio)
{
    struct hm2_sim_inproc *ib = ib_of(llio);
    int n = ib->wn;
    ib->wn = 0;
    ib->wlen = 0;
    if (n == 0)
        return 0;
    for (int i = 0; i < n; i++) /* wbuf may have moved while queueing */
        ib->wsrc[i] = ib->wbuf + ib->woff[i];
    pthread_mutex_lock(&ib->lock);
    struct flush_meter m;
    meter_start(ib, &m);
    int r = ib->api->write(ib->vb, host_time(ib), ib->wx, ib->wsrc, (size_t)n);
    meter_stop(ib, &m);
    ib->write_flushes++;
    pthread_mutex_unlock(&ib->lock);
    if (r) {
        char what[64];
        snprintf(what, sizeof(what), "queued write of %d transfers", n);
        return failed(ib, r, what);
    }
    return 0;
}

/* ---- configuration port ---- */

static int ip_reset(hm2_llio_t *llio)
{
    struct hm2_sim_inproc *ib = ib_of(llio);
    struct vb_config_status st;
    pthread_mutex_lock(&ib->lock);
    int r = ib->api->config(ib->vb, host_time(ib), VB_CONFIG_RESET, NULL, 0, &st);
    pthread_mutex_unlock(&ib->lock);
    if (r)
        return failed(ib, r, "FPGA reset");
    if (st.done || !st.init) {
        IB_LOG(ib, HM2_ERR, "%s: FPGA did not reset: DONE is %s and /INIT is %s after the "
                            "reset (want DONE low, /INIT high)",
               ib->llio.name, st.done ? "high" : "low", st.init ? "high" : "low");
        return -EIO;
    }
    ib->hello.state = VB_STATE_BLANK;
    return 0;
}

static int ip_program_fpga(hm2_llio_t *llio, const struct hm2_bitfile *bf)
{
    struct hm2_sim_inproc *ib = ib_of(llio);
    struct vb_config_status st;
    pthread_mutex_lock(&ib->lock);
    int r = ib->api->config(ib->vb, host_time(ib), VB_CONFIG_PROGRAM, bf->data, bf->size, &st);
    pthread_mutex_unlock(&ib->lock);
    if (r) {
        IB_LOG(ib, HM2_ERR, "%s: the board refused the %u-byte bitstream: %s", ib->llio.name,
               bf->size, ib->api->error(ib->vb));
        return -EIO;
    }
    if (!st.done || !st.init) {
        IB_LOG(ib, HM2_ERR, "%s: FPGA programming failed: DONE is %s and /INIT is %s after "
                            "sending %u bytes (want both high)",
               ib->llio.name, st.done ? "high" : "low", st.init ? "high" : "low", bf->size);
        return -EIO;
    }
    snprintf(ib->hello.firmware, sizeof(ib->hello.firmware), "%.*s", (int)sizeof(st.firmware),
             st.firmware);
    ib->hello.state = VB_STATE_CONFIGURED;
    IB_LOG(ib, HM2_INFO, "%s: board programmed with %s (%u bytes), DONE high", ib->llio.name,
           ib->hello.firmware, bf->size);
    return 0;
}

/* ---- setup ---- */

int hm2_sim_inproc_setup(struct hm2_sim_inproc *ib, const struct hm2_sim_inproc_lib *lib,
                         const char *board, const char *firmware, int index, hm2_sim_now_fn now,
                         hm2_log_fn log, void *log_ctx)
{
    memset(ib, 0, sizeof(*ib));
    ib->api = lib->api;
    ib->now = now;
    ib->log = log;
    ib->log_ctx = log_ctx;
    int r;
    if (!board || !*board) {
        IB_LOG(ib, HM2_ERR, "hm2_sim: inproc=1 needs board=NAME for every board");
        return -EINVAL;
    }
    if (pthread_mutex_init(&ib->lock, NULL)) {
        IB_LOG(ib, HM2_ERR, "hm2_sim: cannot create the lock of in-process board %s", board);
        return -ENOMEM;
    }
    ib->lock_ok = 1;
    char err[512];
    ib->vb = ib->api->open(board, firmware, err, sizeof(err));
    if (!ib->vb) {
        IB_LOG(ib, HM2_ERR, "hm2_sim: %s", err);
        r = -ENODEV;
        goto fail;
    }
    ib->api->hello(ib->vb, &ib->hello);
    ib->info = hm2_board_lookup(ib->hello.board);
    if (!ib->info) {
        IB_LOG(ib, HM2_ERR, "hm2_sim: in-process board '%s' is not in the board table",
               ib->hello.board);
        r = -ENODEV;
        goto fail;
    }
    hm2_llio_t *l = &ib->llio;
    hm2_board_fill_llio(ib->info, index, l);
    l->priv = ib;
    l->read = ip_read;
    l->write = ip_write;
    l->queue_read = ip_queue_read;
    l->send_queued_reads = ip_send_queued_reads;
    l->queue_write = ip_queue_write;
    l->send_queued_writes = ip_send_queued_writes;
    if (ib->info->programmable) {
        l->reset = ip_reset;
        l->program_fpga = ip_program_fpga;
    }
    return 0;
fail:
    hm2_sim_inproc_teardown(ib);
    return r;
}

int hm2_sim_inproc_loops(struct hm2_sim_inproc *ib, const char *spec)
{
    if (!spec)
        return 0;
    char word[64];
    for (const char *p = spec; *p;) {
        p += strspn(p, " \t");
        size_t n = strcspn(p, " \t");
        if (n == 0)
            break;
        snprintf(word, sizeof(word), "%.*s", (int)n, p);
        p += n;
        unsigned from, to;
        char inv[8] = "", tail;
        int k = sscanf(word, "%u:%u:%7[a-z]%c", &from, &to, inv, &tail);
        int ok = k == 2 || (k == 3 && strcmp(inv, "inv") == 0);
        if (!ok || strspn(word, "0123456789:inv") != n) {
            IB_LOG(ib, HM2_ERR, "hm2_sim: bad loop '%s': want FROM:TO or FROM:TO:inv (I/O pin "
                                "numbers)", word);
            return -EINVAL;
        }
        pthread_mutex_lock(&ib->lock);
        int r = ib->api->loop(ib->vb, from, to, k == 3);
        pthread_mutex_unlock(&ib->lock);
        if (r) {
            IB_LOG(ib, HM2_ERR, "hm2_sim: loop %s: %s", word, ib->api->error(ib->vb));
            return r;
        }
    }
    return 0;
}

void hm2_sim_inproc_report(struct hm2_sim_inproc *ib)
{
    if (!ib->vb || !ib->stats)
        return;
    pthread_mutex_lock(&ib->lock);
    uint64_t periods = ib->read_flushes, flush_ns = ib->flush_ns, model_ns = ib->model_ns;
    uint64_t rd = ib->words_read, wr = ib->words_written;
    pthread_mutex_unlock(&ib->lock);
    if (periods == 0) {
        IB_LOG(ib, HM2_PRINT, "%s: in-process board: no queued reads yet", ib->llio.name);
        return;
    }
    double per = (double)flush_ns / (double)periods;
    double model = (double)model_ns / (double)periods;
    IB_LOG(ib, HM2_PRINT,
           "%s: in-process board: %llu cycles (queued reads + writes); per cycle %.0f ns in the "
           "board calls, %.0f ns in the model, %.0f ns transport; %.1f words read, %.1f written",
           ib->llio.name, (unsigned long long)periods, per, model, per - model,
           (double)rd / (double)periods, (double)wr / (double)periods);
}

int hm2_sim_inproc_freerun(struct hm2_sim_inproc *ib)
{
    pthread_mutex_lock(&ib->lock);
    int r = ib->api->freerun(ib->vb, 1);
    pthread_mutex_unlock(&ib->lock);
    if (r)
        IB_LOG(ib, HM2_ERR, "hm2_sim: freerun: %s", ib->api->error(ib->vb));
    return r;
}

void hm2_sim_inproc_teardown(struct hm2_sim_inproc *ib)
{
    if (ib->vb)
        ib->api->close(ib->vb);
    ib->vb = NULL;
    free(ib->rx);
    free(ib->rdest);
    free(ib->wx);
    free(ib->woff);
    free(ib->wsrc);
    free(ib->wbuf);
    ib->rx = NULL, ib->rdest = NULL, ib->wx = NULL, ib->woff = NULL, ib->wsrc = NULL;
    ib->wbuf = NULL;
    ib->rn = ib->rcap = ib->wn = ib->wcap = 0;
    ib->wlen = ib->wbcap = 0;
    if (ib->lock_ok)
        pthread_mutex_destroy(&ib->lock);
    ib->lock_ok = 0;
}
