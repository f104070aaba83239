/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halview.c - see halview.h.  Names and values through hal_query.h only;
 * the scope through scope_rt's shared memory blocks (scope_shm.h).
 */
#define _GNU_SOURCE
#include "halview.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal.h"
#include "hal_query.h"
#include "rtapi.h"
#include "scope_shm.h"

#define SETERR(...)                                 \
    do {                                            \
        if (err != NULL && errlen > 0)              \
            snprintf(err, errlen, __VA_ARGS__);     \
    } while (0)

int hv_attach(void) { return hal_q_attach(); }
int hv_session_exists(void) { return hal_q_session_exists(); }
int hv_simclock(void) { return hal_q_simclock(); }
long long hv_time(void) { return hal_q_time(); }

/* A growing text buffer that counts what it could not store. */
typedef struct {
    char *buf;
    size_t len, used;
} outbuf_t;

static void out_add(outbuf_t *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void out_add(outbuf_t *o, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    size_t room = o->used < o->len ? o->len - o->used : 0;
    int n = vsnprintf(room ? o->buf + o->used : NULL, room, fmt, ap);
    va_end(ap);
    if (n > 0)
        o->used += (size_t)n;
    if (o->len > 0)
        o->buf[o->used < o->len ? o->used : o->len - 1] = '\0';
}

static int list_cb(const char *name, void *ctx)
{
    out_add(ctx, "%s\n", name);
    return 0;
}

long hv_list(int kind, const char *pattern, char *buf, size_t len)
{
    if (kind < HV_COMP || kind > HV_THREAD)
        return -EINVAL;
    int r = hal_q_attach();
    if (r < 0)
        return r;
    outbuf_t o = {buf, len, 0};
    if (len > 0)
        buf[0] = '\0';
    hal_q_foreach((hal_q_kind_t)kind, pattern, list_cb, &o);
    return (long)o.used;
}

static long info_pin(const char *name, outbuf_t *o, int param)
{
    hal_q_pin_t p;
    int r = param ? hal_q_param(name, &p) : hal_q_pin(name, &p);
    if (r < 0)
        return r;
    char v[64];
    hal_q_format_value(p.type, &p.value, v, sizeof(v));
    const char *dir = param ? hal_param_dir_name((hal_param_dir_t)p.dir)
                            : hal_pin_dir_name((hal_pin_dir_t)p.dir);
    if (param)
        out_add(o, "%s\t%s\t%s\t%s", hal_type_name(p.type), dir, v, p.owner);
    else
        out_add(o, "%s\t%s\t%s\t%s\t%s", hal_type_name(p.type), dir, v, p.signal, p.owner);
    return 0;
}

static long info_sig(const char *name, outbuf_t *o)
{
    hal_q_sig_t s;
    int r = hal_q_sig(name, &s);
    if (r < 0)
        return r;
    char v[64];
    hal_q_format_value(s.type, &s.value, v, sizeof(v));
    out_add(o, "%s\t%s\t%d\t%d\t%d\t", hal_type_name(s.type), v, s.writers, s.readers,
            s.bidirs);
    char names[64][HAL_NAME_LEN + 1];
    int n = hal_q_sig_pins(name, names, 64);
    for (int i = 0; i < n && i < 64; i++)
        out_add(o, "%s%s", i ? " " : "", names[i]);
    return 0;
}

static long info_thread(const char *name, outbuf_t *o)
{
    hal_q_thread_t t;
    int r = hal_q_thread(name, &t);
    if (r < 0)
        return r;
    out_add(o, "%ld\t%d\t", t.period, t.uses_fp);
    char names[256][HAL_NAME_LEN + 1];
    int n = hal_q_thread_functs(name, names, 256);
    for (int i = 0; i < n && i < 256; i++)
        out_add(o, "%s%s", i ? " " : "", names[i]);
    return 0;
}

long hv_info(int kind, const char *name, char *buf, size_t len)
{
    int r = hal_q_attach();
    if (r < 0)
        return r;
    if (name == NULL)
        return -EINVAL;
    outbuf_t o = {buf, len, 0};
    if (len > 0)
        buf[0] = '\0';
    long rc;
    switch (kind) {
    case HV_PIN: rc = info_pin(name, &o, 0); break;
    case HV_PARAM: rc = info_pin(name, &o, 1); break;
    case HV_SIG: rc = info_sig(name, &o); break;
    case HV_THREAD: rc = info_thread(name, &o); break;
    case HV_COMP: {
        hal_q_comp_t c;
        rc = hal_q_comp(name, &c);
        if (rc == 0)
            out_add(&o, "%d\t%d\t%d\t%d\t%s", c.id, c.realtime, c.pid, c.ready, c.insmod_args);
        break;
    }
    case HV_FUNCT: {
        hal_q_funct_t f;
        rc = hal_q_funct(name, &f);
        if (rc == 0)
            out_add(&o, "%d\t%d\t%d\t%d", f.owner_id, f.uses_fp, f.reentrant, f.users);
        break;
    }
    default: return -EINVAL;
    }
    return rc < 0 ? rc : (long)o.used;
}

int hv_get(int kind, const char *name, char *buf, size_t len, char *err, size_t errlen)
{
    int r = hal_q_attach();
    if (r < 0) {
        SETERR("cannot attach to HAL (%s)", strerror(-r));
        return r;
    }
    hal_type_t t;
    if (kind == HV_SIG)
        return hal_q_gets(name, buf, len, &t, err, errlen);
    if (kind == HV_PIN || kind == HV_PARAM)
        return hal_q_getp(name, buf, len, &t, err, errlen);
    SETERR("only pins, parameters and signals have values");
    return -EINVAL;
}

int hv_set(int kind, const char *name, const char *value, char *err, size_t errlen)
{
    int r = hal_q_attach();
    if (r < 0) {
        SETERR("cannot attach to HAL (%s)", strerror(-r));
        return r;
    }
    if (kind == HV_SIG)
        return hal_q_sets(name, value, err, errlen);
    if (kind == HV_PIN || kind == HV_PARAM)
        return hal_q_setp(name, value, err, errlen);
    SETERR("only pins, parameters and signals can be set");
    return -EINVAL;
}

long hv_get_many(int n, const int *kinds, const char *names, char *buf, size_t len)
{
    int r = hal_q_attach();
    if (r < 0)
        return r;
    outbuf_t o = {buf, len, 0};
    if (len > 0)
        buf[0] = '\0';
    const char *p = names;
    for (int i = 0; i < n; i++) {
        const char *nl = strchr(p, '\n');
        size_t l = nl ? (size_t)(nl - p) : strlen(p);
        char name[HAL_NAME_LEN + 1];
        char v[64];
        if (l > HAL_NAME_LEN) {
            out_add(&o, "?\n");
        } else {
            memcpy(name, p, l);
            name[l] = '\0';
            if (hv_get(kinds[i], name, v, sizeof(v), NULL, 0) < 0)
                out_add(&o, "?\n");
            else
                out_add(&o, "%s\n", v);
        }
        p += l + (nl ? 1 : 0);
    }
    return (long)o.used;
}

/* ---- scope_rt ------------------------------------------------------------- */

struct hv_scope {
    int ctrl_id, data_id;
    scope_ctrl_t *ctrl;
    hal_data_u *data;
    scope_cfg_t next; /* channels resolved for the next ARM */
};

static int scope_alive(const hv_scope_t *h)
{
    return __atomic_load_n(&h->ctrl->magic, __ATOMIC_ACQUIRE) == SCOPE_MAGIC;
}

hv_scope_t *hv_scope_open(char *err, size_t errlen)
{
    int r = hal_q_attach();
    if (r < 0) {
        SETERR("cannot attach to HAL (%s)", strerror(-r));
        return NULL;
    }
    if (!hal_q_component_exists("scope_rt")) {
        SETERR("scope_rt is not loaded (loadrt scope_rt)");
        return NULL;
    }
    hv_scope_t *h = calloc(1, sizeof(*h));
    void *p;
    if (h == NULL) {
        SETERR("out of memory");
        return NULL;
    }
    h->ctrl_id = rtapi_shmem_new(SCOPE_CTRL_KEY, 0, sizeof(scope_ctrl_t));
    if (h->ctrl_id < 0 || rtapi_shmem_getptr(h->ctrl_id, &p) < 0) {
        SETERR("cannot map scope_rt's control block (%s)", strerror(-h->ctrl_id));
        goto fail;
    }
    h->ctrl = p;
    if (!scope_alive(h) || h->ctrl->version != SCOPE_VERSION) {
        SETERR("scope_rt's control block is not initialized (scope_rt unloading, or "
               "another version)");
        goto fail;
    }
    h->data_id = rtapi_shmem_new(SCOPE_DATA_KEY, 0,
                                 (unsigned long)h->ctrl->num_samples * sizeof(hal_data_u));
    if (h->data_id < 0 || rtapi_shmem_getptr(h->data_id, &p) < 0) {
        SETERR("cannot map scope_rt's sample block (%s)", strerror(-h->data_id));
        goto fail;
    }
    h->data = p;
    return h;
fail:
    hv_scope_close(h);
    return NULL;
}

void hv_scope_close(hv_scope_t *h)
{
    if (h == NULL)
        return;
    if (h->data_id > 0)
        rtapi_shmem_delete(h->data_id, 0);
    if (h->ctrl_id > 0)
        rtapi_shmem_delete(h->ctrl_id, 0);
    free(h);
}

int hv_scope_status(hv_scope_t *h, hv_scope_status_t *st)
{
    scope_ctrl_t *c = h->ctrl;
    if (!scope_alive(h))
        return -ENODEV;
    st->state = __atomic_load_n(&c->state, __ATOMIC_ACQUIRE);
    st->error = c->error;
    st->capture_seq = __atomic_load_n(&c->capture_seq, __ATOMIC_ACQUIRE);
    st->forced = c->forced;
    st->nchan = c->cfg.nchan;
    st->capacity = (int64_t)c->capacity;
    st->widx = (int64_t)__atomic_load_n(&c->widx, __ATOMIC_ACQUIRE);
    st->trig_idx = (int64_t)c->trig_idx;
    st->start_idx = (int64_t)c->start_idx;
    st->t_first = c->t_first;
    st->t_trig = c->t_trig;
    st->interval = c->interval;
    st->lost = (int64_t)c->lost;
    st->calls = (int64_t)c->calls;
    st->num_samples = (int64_t)c->num_samples;
    st->pending = __atomic_load_n(&c->ack_seq, __ATOMIC_ACQUIRE) != c->cmd_seq;
    st->done_calls = (int64_t)c->done_calls;
    return 0;
}

int hv_scope_set_chan(hv_scope_t *h, int i, int kind, const char *name, char *err,
                      size_t errlen)
{
    static const char *what[] = {"component", "pin", "parameter", "signal"};
    if (i < 0 || i >= SCOPE_MAX_CHAN) {
        SETERR("channel %d: the scope has channels 1 to %d", i + 1, SCOPE_MAX_CHAN);
        return -EINVAL;
    }
    if (kind != HV_PIN && kind != HV_PARAM && kind != HV_SIG) {
        SETERR("channel %d: only pins, parameters and signals can be sampled", i + 1);
        return -EINVAL;
    }
    int r = hal_q_ref((hal_q_kind_t)kind, name, &h->next.chan[i]);
    if (r == -ENOENT)
        SETERR("channel %d: %s '%s' does not exist", i + 1, what[kind], name);
    else if (r < 0)
        SETERR("channel %d: %s '%s': %s", i + 1, what[kind], name, strerror(-r));
    return r < 0 ? r : (int)h->next.chan[i].type;
}

static void post_cmd(scope_ctrl_t *c, uint32_t cmd)
{
    c->cmd = cmd;
    __atomic_add_fetch(&c->cmd_seq, 1u, __ATOMIC_RELEASE);
}

int hv_scope_arm(hv_scope_t *h, int nchan, int mult, uint64_t rec_len, uint64_t pretrig,
                 int trig_chan, int edge, double level, int mode, int reader_wait, char *err,
                 size_t errlen)
{
    scope_ctrl_t *c = h->ctrl;
    if (!scope_alive(h)) {
        SETERR("scope_rt was unloaded");
        return -ENODEV;
    }
    if (nchan < 1 || nchan > SCOPE_MAX_CHAN) {
        SETERR("%d channels: the scope samples 1 to %d", nchan, SCOPE_MAX_CHAN);
        return -EINVAL;
    }
    if (mult < 1) {
        SETERR("sample every %d periods: must be 1 or more", mult);
        return -EINVAL;
    }
    uint64_t cap = c->num_samples / (uint64_t)nchan;
    if (mode != SCOPE_MODE_ROLL && (rec_len < 1 || rec_len > cap)) {
        SETERR("record length %" PRIu64 " with %d channels: scope_rt holds %" PRIu64
               " (num_samples=%" PRIu64 ")",
               rec_len, nchan, cap, (uint64_t)c->num_samples);
        return -ERANGE;
    }
    if (mode != SCOPE_MODE_ROLL && pretrig >= rec_len) {
        SETERR("%" PRIu64 " samples before the trigger: the record has %" PRIu64, pretrig,
               rec_len);
        return -ERANGE;
    }
    if (mode < SCOPE_MODE_NORMAL || mode > SCOPE_MODE_ROLL || trig_chan < -1 ||
        trig_chan >= nchan || (edge != SCOPE_RISING && edge != SCOPE_FALLING)) {
        SETERR("bad mode, trigger channel or edge");
        return -EINVAL;
    }
    scope_cfg_t *n = &h->next;
    n->nchan = nchan;
    n->mult = mult;
    n->rec_len = rec_len;
    n->pretrig = pretrig;
    n->trig_chan = trig_chan;
    n->trig_edge = edge;
    n->trig_level = level;
    n->mode = mode;
    n->reader_wait = reader_wait;
    c->reader_pid = reader_wait ? (int32_t)getpid() : 0;
    __atomic_add_fetch(&c->cfg_gen, 1u, __ATOMIC_ACQ_REL); /* odd: writing */
    memcpy((void *)&c->cfg, n, sizeof(*n));
    __atomic_add_fetch(&c->cfg_gen, 1u, __ATOMIC_RELEASE); /* even: done */
    post_cmd(c, SCOPE_CMD_ARM);
    return 0;
}

int hv_scope_stop(hv_scope_t *h)
{
    if (!scope_alive(h))
        return -ENODEV;
    post_cmd(h->ctrl, SCOPE_CMD_STOP);
    return 0;
}

int64_t hv_scope_read(hv_scope_t *h, uint64_t first, uint64_t count, void *out)
{
    scope_ctrl_t *c = h->ctrl;
    uint64_t nchan = (uint64_t)c->cfg.nchan;
    uint64_t cap = c->capacity;
    if (!scope_alive(h) || cap == 0 || nchan == 0)
        return -ENODEV;
    hal_data_u *dst = out;
    uint64_t slot = first % cap;
    for (uint64_t r = 0; r < count; r++) {
        memcpy(dst + r * nchan, h->data + slot * nchan, nchan * sizeof(hal_data_u));
        if (++slot == cap)
            slot = 0;
    }
    __atomic_thread_fence(__ATOMIC_ACQUIRE);
    uint64_t w2 = __atomic_load_n(&c->widx, __ATOMIC_ACQUIRE);
    uint64_t valid = w2 >= cap ? w2 - cap + 1 : 0;
    return (int64_t)(valid > first ? valid : first);
}

void hv_scope_consume(hv_scope_t *h, uint64_t idx)
{
    __atomic_store_n(&h->ctrl->rd_idx, idx, __ATOMIC_RELEASE);
}
