/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_query.c - introspection by name (hal_query.h): lookups, snapshots
 * of every object of a kind, names, memory and lock status.  Values by
 * name are in hal_q_values.c.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fnmatch.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "hal_lib_int.h"
#include "hal_query.h"

int hal_q_attach(void) { return hal_priv_attach(); }

int hal_q_match(const char *pattern, const char *name)
{
    if (pattern == NULL || pattern[0] == '\0')
        return 1;
    if (strncmp(pattern, name, strlen(pattern)) == 0)
        return 1;
    return fnmatch(pattern, name, 0) == 0;
}

static void fill_pin(hal_pin_t *p, hal_q_pin_t *out)
{
    memset(out, 0, sizeof(*out));
    snprintf(out->name, sizeof(out->name), "%s", p->name);
    if (p->oldname)
        snprintf(out->original, sizeof(out->original), "%s",
                 ((hal_oldname_t *)SHMPTR(p->oldname))->name);
    out->type = p->type;
    out->dir = p->dir;
    hal_comp_t *c = SHMPTR(p->owner);
    out->owner_id = c->id;
    snprintf(out->owner, sizeof(out->owner), "%s", c->name);
    if (p->signal)
        snprintf(out->signal, sizeof(out->signal), "%s", ((hal_sig_t *)SHMPTR(p->signal))->name);
    read_typed(p->type, halpr_pin_value(p), &out->value);
}

static void fill_param(hal_param_t *p, hal_q_pin_t *out)
{
    memset(out, 0, sizeof(*out));
    snprintf(out->name, sizeof(out->name), "%s", p->name);
    if (p->oldname)
        snprintf(out->original, sizeof(out->original), "%s",
                 ((hal_oldname_t *)SHMPTR(p->oldname))->name);
    out->type = p->type;
    out->dir = p->dir;
    hal_comp_t *c = SHMPTR(p->owner);
    out->owner_id = c->id;
    snprintf(out->owner, sizeof(out->owner), "%s", c->name);
    read_typed(p->type, halpr_param_value(p), &out->value);
}

int hal_q_pin(const char *name, hal_q_pin_t *out)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_pin_t *p = halpr_find_pin_by_name(name);
    if (p != NULL && out != NULL)
        fill_pin(p, out);
    hal_priv_unlock();
    return p ? 0 : -ENOENT;
}

int hal_q_param(const char *name, hal_q_pin_t *out)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_param_t *p = halpr_find_param_by_name(name);
    if (p != NULL && out != NULL)
        fill_param(p, out);
    hal_priv_unlock();
    return p ? 0 : -ENOENT;
}

int hal_q_sig(const char *name, hal_q_sig_t *out)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_sig_t *s = halpr_find_sig_by_name(name);
    if (s != NULL && out != NULL) {
        memset(out, 0, sizeof(*out));
        snprintf(out->name, sizeof(out->name), "%s", s->name);
        out->type = s->type;
        out->readers = s->readers;
        out->writers = s->writers;
        out->bidirs = s->bidirs;
        read_typed(s->type, halpr_sig_value(s), &out->value);
    }
    hal_priv_unlock();
    return s ? 0 : -ENOENT;
}

static void fill_comp(hal_comp_t *c, hal_q_comp_t *out)
{
    memset(out, 0, sizeof(*out));
    snprintf(out->name, sizeof(out->name), "%s", c->name);
    out->id = c->id;
    out->realtime = c->type == HAL_COMP_RT;
    out->pid = c->pid;
    out->ready = c->ready;
    out->loaded_by_loadrt = c->loaded_by_loadrt;
    if (c->insmod_args)
        snprintf(out->insmod_args, sizeof(out->insmod_args), "%s",
                 (char *)SHMPTR(c->insmod_args));
}

int hal_q_comp(const char *name, hal_q_comp_t *out)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_comp_t *c = halpr_find_comp_by_name(name);
    if (c != NULL && out != NULL)
        fill_comp(c, out);
    hal_priv_unlock();
    return c ? 0 : -ENOENT;
}

static void fill_funct(hal_funct_t *f, hal_q_funct_t *out)
{
    memset(out, 0, sizeof(*out));
    snprintf(out->name, sizeof(out->name), "%s", f->name);
    hal_comp_t *c = SHMPTR(f->owner);
    out->owner_id = c->id;
    snprintf(out->owner, sizeof(out->owner), "%s", c->name);
    out->uses_fp = f->uses_fp;
    out->reentrant = f->reentrant;
    out->users = f->users;
    out->code_addr = f->funct;
    out->arg = f->arg;
}

int hal_q_funct(const char *name, hal_q_funct_t *out)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_funct_t *f = halpr_find_funct_by_name(name);
    if (f != NULL && out != NULL)
        fill_funct(f, out);
    hal_priv_unlock();
    return f ? 0 : -ENOENT;
}

static void fill_thread(hal_thread_t *t, hal_q_thread_t *out)
{
    memset(out, 0, sizeof(*out));
    snprintf(out->name, sizeof(out->name), "%s", t->name);
    out->period = t->period;
    out->uses_fp = t->uses_fp;
    out->comp_id = t->comp_id;
    for (hal_off_t off = t->funct_list; off; off = ((hal_funct_entry_t *)SHMPTR(off))->next)
        out->nfuncts++;
    char pname[HAL_NAME_LEN + 8];
    snprintf(pname, sizeof(pname), "%s.time", t->name);
    hal_pin_t *p = halpr_find_pin_by_name(pname);
    out->runtime = p ? (long)halpr_pin_value(p)->s : 0;
    out->maxtime = *(hal_s32_t *)SHMPTR(t->maxtime);
}

int hal_q_thread(const char *name, hal_q_thread_t *out)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_thread_t *t = halpr_find_thread_by_name(name);
    if (t != NULL && out != NULL)
        fill_thread(t, out);
    hal_priv_unlock();
    return t ? 0 : -ENOENT;
}

int hal_q_thread_functs(const char *thread, char (*names)[HAL_NAME_LEN + 1], int max)
{
    if (thread == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_thread_t *t = halpr_find_thread_by_name(thread);
    int n = 0;
    if (t != NULL) {
        for (hal_off_t off = t->funct_list; off;) {
            hal_funct_entry_t *e = SHMPTR(off);
            if (n < max && names != NULL)
                snprintf(names[n], HAL_NAME_LEN + 1, "%s",
                         ((hal_funct_t *)SHMPTR(e->funct))->name);
            n++;
            off = e->next;
        }
    }
    hal_priv_unlock();
    return t ? n : -ENOENT;
}

int hal_q_sig_pins(const char *sig, char (*names)[HAL_NAME_LEN + 1], int max)
{
    if (sig == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_sig_t *s = halpr_find_sig_by_name(sig);
    int n = 0;
    if (s != NULL) {
        for (hal_off_t off = hal_hdr->pin_list; off;) {
            hal_pin_t *p = SHMPTR(off);
            if (p->signal == SHMOFF(s)) {
                if (n < max && names != NULL)
                    snprintf(names[n], HAL_NAME_LEN + 1, "%s", p->name);
                n++;
            }
            off = p->next;
        }
    }
    hal_priv_unlock();
    return s ? n : -ENOENT;
}

int hal_q_foreach(hal_q_kind_t kind, const char *pattern, hal_q_name_cb cb, void *ctx)
{
    if (hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_off_t head;
    size_t name_off;
    switch (kind) {
    case HAL_Q_COMP: head = hal_hdr->comp_list; name_off = offsetof(hal_comp_t, name); break;
    case HAL_Q_PIN:
    case HAL_Q_PIN_ALIAS: head = hal_hdr->pin_list; name_off = offsetof(hal_pin_t, name); break;
    case HAL_Q_PARAM:
    case HAL_Q_PARAM_ALIAS:
        head = hal_hdr->param_list;
        name_off = offsetof(hal_param_t, name);
        break;
    case HAL_Q_SIG: head = hal_hdr->sig_list; name_off = offsetof(hal_sig_t, name); break;
    case HAL_Q_FUNCT: head = hal_hdr->funct_list; name_off = offsetof(hal_funct_t, name); break;
    case HAL_Q_THREAD:
        head = hal_hdr->thread_list;
        name_off = offsetof(hal_thread_t, name);
        break;
    default: hal_priv_unlock(); return -EINVAL;
    }
    size_t cap = 64, n = 0;
    char(*names)[HAL_NAME_LEN + 1] = malloc(cap * sizeof(*names));
    if (names == NULL) {
        hal_priv_unlock();
        return -ENOMEM;
    }
    for (hal_off_t off = head; off != 0; off = *(hal_off_t *)SHMPTR(off)) {
        char *obj = SHMPTR(off);
        if (kind == HAL_Q_PIN_ALIAS && ((hal_pin_t *)obj)->oldname == 0)
            continue;
        if (kind == HAL_Q_PARAM_ALIAS && ((hal_param_t *)obj)->oldname == 0)
            continue;
        const char *nm = obj + name_off;
        if (!hal_q_match(pattern, nm))
            continue;
        if (n == cap) {
            cap *= 2;
            void *nn = realloc(names, cap * sizeof(*names));
            if (nn == NULL) {
                free(names);
                hal_priv_unlock();
                return -ENOMEM;
            }
            names = nn;
        }
        snprintf(names[n++], HAL_NAME_LEN + 1, "%s", nm);
    }
    hal_priv_unlock();
    size_t i;
    for (i = 0; i < n; i++)
        if (cb != NULL && cb(names[i], ctx) != 0) {
            i++;
            break;
        }
    free(names);
    return (int)i;
}

int hal_q_pin_has_writer(const char *name)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_pin_t *p = halpr_find_pin_by_name(name);
    int rc = -ENOENT;
    if (p != NULL) {
        rc = 0;
        if (p->signal != 0) {
            hal_sig_t *s = SHMPTR(p->signal);
            rc = (s->writers + s->bidirs) > 0;
        }
    }
    hal_priv_unlock();
    return rc;
}

int hal_q_component_exists(const char *name)
{
    return hal_q_comp(name, NULL) == 0;
}

int hal_q_component_ready(const char *name)
{
    hal_q_comp_t c;
    if (hal_q_comp(name, &c) != 0)
        return 0;
    return c.ready;
}

unsigned long hal_q_shm_offset(const volatile void *ptr)
{
    if (hal_priv_attach() != 0 || !SHMCHK(ptr))
        return 0;
    return (unsigned long)((const char *)ptr - hal_shmem_base);
}

void *hal_q_shm_ptr(unsigned long offset)
{
    if (hal_priv_attach() != 0 || offset == 0 || offset >= hal_hdr->size)
        return NULL;
    return SHMPTR(offset);
}

int hal_q_simclock(void) { return rtapi_is_simclock(); }

long long hal_q_time(void)
{
    hal_priv_attach();
    return rtapi_get_time();
}

/* ---- snapshots ---------------------------------------------------------------- */

typedef void (*fill_fn)(void *obj, void *out);

static void fill_comp_v(void *o, void *out) { fill_comp(o, out); }
static void fill_pin_v(void *o, void *out) { fill_pin(o, out); }
static void fill_param_v(void *o, void *out) { fill_param(o, out); }
static void fill_funct_v(void *o, void *out) { fill_funct(o, out); }
static void fill_thread_v(void *o, void *out) { fill_thread(o, out); }
static void fill_sig_v(void *o, void *out)
{
    hal_sig_t *s = o;
    hal_q_sig_t *q = out;
    memset(q, 0, sizeof(*q));
    snprintf(q->name, sizeof(q->name), "%s", s->name);
    q->type = s->type;
    q->readers = s->readers;
    q->writers = s->writers;
    q->bidirs = s->bidirs;
    read_typed(s->type, halpr_sig_value(s), &q->value);
}

/* Copy every object of the list starting at *head (each object starts
 * with its `next` offset) into a malloc'd array of `size`-byte records. */
static int snapshot(const hal_off_t *head, size_t size, fill_fn fill, char **out)
{
    *out = NULL;
    if (hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    size_t n = 0;
    for (hal_off_t off = *head; off != 0; off = *(hal_off_t *)SHMPTR(off))
        n++;
    char *v = malloc(n ? n * size : 1);
    if (v == NULL) {
        hal_priv_unlock();
        return -ENOMEM;
    }
    size_t i = 0;
    for (hal_off_t off = *head; off != 0 && i < n; off = *(hal_off_t *)SHMPTR(off))
        fill(SHMPTR(off), v + size * i++);
    hal_priv_unlock();
    *out = v;
    return (int)i;
}

#define EACH(fn, head, qtype, cbtype, filler)                                            \
    int fn(cbtype cb, void *ctx)                                                         \
    {                                                                                    \
        if (hal_priv_attach() != 0)                                                      \
            return -EINVAL;                                                              \
        char *v;                                                                         \
        int n = snapshot(&hal_hdr->head, sizeof(qtype), filler, &v);                     \
        if (n < 0)                                                                       \
            return n;                                                                    \
        int i = 0;                                                                       \
        while (i < n && (cb == NULL || cb((const qtype *)(v + sizeof(qtype) * (size_t)i), \
                                          ctx) == 0))                                    \
            i++;                                                                         \
        free(v);                                                                         \
        return i < n ? i + 1 : n;                                                        \
    }
EACH(hal_q_each_comp, comp_list, hal_q_comp_t, hal_q_comp_cb, fill_comp_v)
EACH(hal_q_each_pin, pin_list, hal_q_pin_t, hal_q_pin_cb, fill_pin_v)
EACH(hal_q_each_param, param_list, hal_q_pin_t, hal_q_pin_cb, fill_param_v)
EACH(hal_q_each_sig, sig_list, hal_q_sig_t, hal_q_sig_cb, fill_sig_v)
EACH(hal_q_each_funct, funct_list, hal_q_funct_t, hal_q_funct_cb, fill_funct_v)
EACH(hal_q_each_thread, thread_list, hal_q_thread_t, hal_q_thread_cb, fill_thread_v)

int hal_q_status(hal_q_status_t *out)
{
    if (out == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    const hal_hdr_t *h = hal_hdr;
    out->lock = h->lock;
    out->shmem_total = (long)h->size;
    out->shmem_used = (long)(h->size - (h->top - h->bot));
    out->active_comps = h->active_comps;
    out->active_pins = h->active_pins;
    out->active_params = h->active_params;
    out->active_aliases = h->active_aliases;
    out->active_sigs = h->active_sigs;
    out->active_functs = h->active_functs;
    out->active_threads = h->active_threads;
    out->recycled_comps = h->recycled_comps;
    out->recycled_pins = h->recycled_pins;
    out->recycled_params = h->recycled_params;
    out->recycled_aliases = h->recycled_aliases;
    out->recycled_sigs = h->recycled_sigs;
    out->recycled_functs = h->recycled_functs;
    out->recycled_threads = h->recycled_threads;
    hal_priv_unlock();
    return 0;
}
