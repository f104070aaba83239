/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_objects.c - what every part of libhal builds on: carving objects
 * from the segment and recycling them, hal_malloc, the per-kind lists in
 * show order with their name indexes, lookups by name, name checks, the
 * lock, and the names of types and directions.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_lib_int.h"

static int realtime_host;
const hal_thread_hooks_t *hal_thread_hooks;

void hal_priv_set_realtime_host(int yes) { realtime_host = yes; }
int hal_priv_is_realtime_host(void) { return realtime_host; }
void hal_priv_set_thread_hooks(const hal_thread_hooks_t *hooks) { hal_thread_hooks = hooks; }

/* ---- allocation ---------------------------------------------------------- */

void *alloc_obj(size_t size, hal_off_t *free_list, int *recycled)
{
    if (*free_list != 0) {
        hal_off_t off = *free_list;
        void *p = SHMPTR(off);
        *free_list = *(hal_off_t *)p;
        if (recycled)
            (*recycled)--;
        memset(p, 0, size);
        return p;
    }
    size = (size + 7) & ~(size_t)7;
    if (hal_hdr->bot + size > hal_hdr->top)
        return NULL;
    void *p = SHMPTR(hal_hdr->bot);
    hal_hdr->bot += (uint32_t)size;
    memset(p, 0, size);
    return p;
}

void free_obj(void *p, hal_off_t *free_list, int *recycled)
{
    *(hal_off_t *)p = *free_list;
    *free_list = SHMOFF(p);
    if (recycled)
        (*recycled)++;
}

void *shmalloc_dn(size_t size)
{
    /* As malloc: blocks that can hold any type are aligned for any type
     * (a component's state may contain long double or 16-aligned data). */
    size_t align = size >= 16 ? 16 : size >= 8 ? 8 : (size >= 4 ? 4 : (size >= 2 ? 2 : 1));
    uint32_t top = hal_hdr->top - (uint32_t)size;
    top &= ~(uint32_t)(align - 1);
    if (top < hal_hdr->bot || size > hal_hdr->top)
        return NULL;
    hal_hdr->top = top;
    void *p = SHMPTR(top);
    memset(p, 0, size);
    return p;
}

void *hal_malloc(long size)
{
    if (size <= 0) {
        ERR("HAL: ERROR: hal_malloc called with size %ld\n", size);
        return NULL;
    }
    if (hal_priv_attach() != 0)
        return NULL;
    hal_priv_lock();
    void *p = shmalloc_dn((size_t)size);
    hal_priv_unlock();
    if (p == NULL)
        ERR("HAL: ERROR: insufficient memory for hal_malloc(%ld)\n", size);
    return p;
}

/* ---- name indexes and lists ------------------------------------------------ */
/*
 * Every kind of named object is on a list in show order (sorted by name;
 * components and threads newest first) and in a hash index by name, so
 * lookups and insertions stay cheap when a configuration has thousands of
 * pins.  `next` and `hnext` are the first two fields of every indexed
 * struct.
 */

static const size_t name_offsets[6] = {
    offsetof(hal_comp_t, name),  offsetof(hal_pin_t, name),   offsetof(hal_param_t, name),
    offsetof(hal_sig_t, name),   offsetof(hal_funct_t, name), offsetof(hal_thread_t, name),
};

static hal_off_t *list_head(int kind)
{
    switch (kind) {
    case HAL_IDX_COMP: return &hal_hdr->comp_list;
    case HAL_IDX_PIN: return &hal_hdr->pin_list;
    case HAL_IDX_PARAM: return &hal_hdr->param_list;
    case HAL_IDX_SIG: return &hal_hdr->sig_list;
    case HAL_IDX_FUNCT: return &hal_hdr->funct_list;
    default: return &hal_hdr->thread_list;
    }
}

static uint32_t name_hash(const char *s)
{
    uint32_t h = 2166136261u; /* FNV-1a */
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 16777619u;
    return h & (HAL_HASH_SIZE - 1);
}

static const char *obj_name(int kind, void *obj) { return (const char *)obj + name_offsets[kind]; }
static hal_off_t *obj_next(void *obj) { return (hal_off_t *)obj; }
static hal_off_t *obj_hnext(void *obj) { return (hal_off_t *)obj + 1; }

static void idx_add(int kind, void *obj)
{
    hal_off_t *bucket = (hal_off_t *)SHMPTR(hal_hdr->idx[kind]) + name_hash(obj_name(kind, obj));
    *obj_hnext(obj) = *bucket;
    *bucket = SHMOFF(obj);
}

static void idx_del(int kind, void *obj)
{
    hal_off_t *pp = (hal_off_t *)SHMPTR(hal_hdr->idx[kind]) + name_hash(obj_name(kind, obj));
    hal_off_t target = SHMOFF(obj);
    while (*pp != 0) {
        if (*pp == target) {
            *pp = *obj_hnext(obj);
            return;
        }
        pp = obj_hnext(SHMPTR(*pp));
    }
}

static void *idx_find(int kind, const char *name)
{
    hal_off_t off = ((hal_off_t *)SHMPTR(hal_hdr->idx[kind]))[name_hash(name)];
    while (off != 0) {
        void *o = SHMPTR(off);
        if (strcmp(obj_name(kind, o), name) == 0)
            return o;
        off = *obj_hnext(o);
    }
    return NULL;
}

/* Sorted insertion (strcmp order, like LinuxCNC's lists); components
 * usually create names in order, so the last insertion point is tried
 * first. */
void list_insert_sorted(int kind, void *obj)
{
    const char *name = obj_name(kind, obj);
    hal_off_t *prev = list_head(kind);
    hal_off_t hint = hal_hdr->hint[kind];
    if (hint != 0 && strcmp(obj_name(kind, SHMPTR(hint)), name) < 0)
        prev = obj_next(SHMPTR(hint));
    while (*prev != 0) {
        void *o = SHMPTR(*prev);
        if (strcmp(obj_name(kind, o), name) > 0)
            break;
        prev = obj_next(o);
    }
    *obj_next(obj) = *prev;
    *prev = SHMOFF(obj);
    hal_hdr->hint[kind] = SHMOFF(obj);
    idx_add(kind, obj);
}

/* Newest-first insertion (components, threads). */
void list_insert_front(int kind, void *obj)
{
    hal_off_t *head = list_head(kind);
    *obj_next(obj) = *head;
    *head = SHMOFF(obj);
    idx_add(kind, obj);
}

void list_remove(int kind, void *obj)
{
    hal_off_t target = SHMOFF(obj);
    hal_off_t *prev = list_head(kind);
    while (*prev != 0) {
        if (*prev == target) {
            *prev = *obj_next(obj);
            break;
        }
        prev = obj_next(SHMPTR(*prev));
    }
    if (hal_hdr->hint[kind] == target)
        hal_hdr->hint[kind] = 0;
    idx_del(kind, obj);
}

/* Remove when the caller already holds the predecessor link. */
void list_remove_at(int kind, hal_off_t *prev, void *obj)
{
    *prev = *obj_next(obj);
    if (hal_hdr->hint[kind] == SHMOFF(obj))
        hal_hdr->hint[kind] = 0;
    idx_del(kind, obj);
}

hal_comp_t *halpr_find_comp_by_name(const char *name) { return idx_find(HAL_IDX_COMP, name); }

hal_comp_t *halpr_find_comp_by_id(int id)
{
    for (hal_off_t off = hal_hdr->comp_list; off != 0;) {
        hal_comp_t *c = SHMPTR(off);
        if (c->id == id)
            return c;
        off = c->next;
    }
    return NULL;
}

hal_pin_t *halpr_find_pin_by_name(const char *name)
{
    hal_pin_t *p = idx_find(HAL_IDX_PIN, name);
    if (p != NULL || hal_hdr->active_aliases == 0)
        return p;
    /* by original name of an aliased pin */
    for (hal_off_t off = hal_hdr->pin_list; off != 0;) {
        p = SHMPTR(off);
        if (p->oldname != 0 && strcmp(((hal_oldname_t *)SHMPTR(p->oldname))->name, name) == 0)
            return p;
        off = p->next;
    }
    return NULL;
}

hal_param_t *halpr_find_param_by_name(const char *name)
{
    hal_param_t *p = idx_find(HAL_IDX_PARAM, name);
    if (p != NULL || hal_hdr->active_aliases == 0)
        return p;
    for (hal_off_t off = hal_hdr->param_list; off != 0;) {
        p = SHMPTR(off);
        if (p->oldname != 0 && strcmp(((hal_oldname_t *)SHMPTR(p->oldname))->name, name) == 0)
            return p;
        off = p->next;
    }
    return NULL;
}

hal_sig_t *halpr_find_sig_by_name(const char *name) { return idx_find(HAL_IDX_SIG, name); }
hal_funct_t *halpr_find_funct_by_name(const char *name) { return idx_find(HAL_IDX_FUNCT, name); }
hal_thread_t *halpr_find_thread_by_name(const char *name) { return idx_find(HAL_IDX_THREAD, name); }

hal_data_u *halpr_pin_value(hal_pin_t *pin)
{
    if (pin->signal != 0)
        return halpr_sig_value(SHMPTR(pin->signal));
    return &pin->dummysig;
}

void *halpr_param_value(hal_param_t *param) { return SHMPTR(param->data_ptr); }

hal_data_u *halpr_sig_value(hal_sig_t *sig) { return SHMPTR(sig->data_ptr); }

int halpr_next_id(void) { return hal_hdr->next_id++; }

int check_name(const char *what, const char *name)
{
    if (name == NULL || name[0] == '\0') {
        ERR("HAL: ERROR: %s name is empty\n", what);
        return -EINVAL;
    }
    if (strlen(name) > HAL_NAME_LEN) {
        ERR("HAL: ERROR: %s name '%s' is too long\n", what, name);
        return -EINVAL;
    }
    return 0;
}

int name_in_use_pin(const char *name)
{
    return halpr_find_pin_by_name(name) != NULL;
}
/* ---- lock ---------------------------------------------------------------- */

int hal_set_lock(unsigned char lock_type)
{
    if (hal_priv_attach() != 0)
        return -EINVAL;
    hal_hdr->lock = lock_type;
    return 0;
}

unsigned char hal_get_lock(void)
{
    if (hal_priv_attach() != 0)
        return 0;
    return hal_hdr->lock;
}
/* ---- helpers ------------------------------------------------------------- */

const char *hal_type_name(hal_type_t type)
{
    switch (type) {
    case HAL_BIT: return "bit";
    case HAL_FLOAT: return "float";
    case HAL_S32: return "s32";
    case HAL_U32: return "u32";
    case HAL_S64: return "s64";
    case HAL_U64: return "u64";
    case HAL_PORT: return "port";
    default: return "undef";
    }
}

const char *hal_pin_dir_name(hal_pin_dir_t dir)
{
    switch (dir) {
    case HAL_IN: return "IN";
    case HAL_OUT: return "OUT";
    case HAL_IO: return "I/O";
    default: return "???";
    }
}

const char *hal_param_dir_name(hal_param_dir_t dir)
{
    switch (dir) {
    case HAL_RO: return "RO";
    case HAL_RW: return "RW";
    default: return "??";
    }
}

int vformat_name(char *buf, const char *what, const char *fmt, va_list ap)
{
    int n = vsnprintf(buf, HAL_NAME_LEN + 1, fmt, ap);
    if (n < 0 || n > HAL_NAME_LEN) {
        ERR("HAL: ERROR: %s name '%s...' is too long\n", what, buf);
        return -ENOMEM;
    }
    return 0;
}

int valid_type(int type)
{
    return type == HAL_BIT || type == HAL_FLOAT || type == HAL_S32 || type == HAL_U32 ||
           type == HAL_S64 || type == HAL_U64;
}
