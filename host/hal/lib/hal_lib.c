/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_lib.c - the HAL API of hal.h: components, pins, parameters, signals,
 * functions, threads and the lock, all kept in the shared segment.
 *
 * Every public function takes the mutex, checks everything it needs before
 * it changes anything (a failed call changes nothing), and prints one
 * "HAL: ERROR: ..." line that names the object and the reason, with the
 * wording LinuxCNC 2.9 uses where it has one.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_priv.h"

static int realtime_host;
static const hal_thread_hooks_t *thread_hooks;

void hal_priv_set_realtime_host(int yes) { realtime_host = yes; }
int hal_priv_is_realtime_host(void) { return realtime_host; }
void hal_priv_set_thread_hooks(const hal_thread_hooks_t *hooks) { thread_hooks = hooks; }

#define ERR(...) rtapi_print_msg(RTAPI_MSG_ERR, __VA_ARGS__)

/* ---- allocation ---------------------------------------------------------- */

static void *alloc_obj(size_t size, hal_off_t *free_list, int *recycled)
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

static void free_obj(void *p, hal_off_t *free_list, int *recycled)
{
    *(hal_off_t *)p = *free_list;
    *free_list = SHMOFF(p);
    if (recycled)
        (*recycled)++;
}

static void *shmalloc_dn(size_t size)
{
    size_t align = size >= 8 ? 8 : (size >= 4 ? 4 : (size >= 2 ? 2 : 1));
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
static void list_insert_sorted(int kind, void *obj)
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
static void list_insert_front(int kind, void *obj)
{
    hal_off_t *head = list_head(kind);
    *obj_next(obj) = *head;
    *head = SHMOFF(obj);
    idx_add(kind, obj);
}

static void list_remove(int kind, void *obj)
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
static void list_remove_at(int kind, hal_off_t *prev, void *obj)
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

static int check_name(const char *what, const char *name)
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

static int name_in_use_pin(const char *name)
{
    return halpr_find_pin_by_name(name) != NULL;
}

/* ---- components ------------------------------------------------------------ */

static int comp_create_locked(const char *name, int type, int ready)
{
    if (halpr_find_comp_by_name(name) != NULL) {
        ERR("HAL: ERROR: duplicate component name '%s'\n", name);
        return -EEXIST;
    }
    hal_comp_t *c = alloc_obj(sizeof(hal_comp_t), &hal_hdr->comp_free, &hal_hdr->recycled_comps);
    if (c == NULL) {
        ERR("HAL: ERROR: insufficient memory for component '%s'\n", name);
        return -ENOMEM;
    }
    c->id = halpr_next_id();
    c->type = type;
    c->ready = ready;
    c->pid = type == HAL_COMP_USER ? getpid() : 0;
    c->shmem_base = (uint64_t)(uintptr_t)hal_shmem_base;
    snprintf(c->name, sizeof(c->name), "%s", name);
    list_insert_front(HAL_IDX_COMP, c); /* newest first, as LinuxCNC lists them */
    hal_hdr->active_comps++;
    return c->id;
}

int hal_init(const char *name)
{
    int rc = check_name("component", name);
    if (rc)
        return rc;
    rc = hal_priv_attach();
    if (rc)
        return rc;
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_LOAD) {
        hal_priv_unlock();
        ERR("HAL: ERROR: hal_init called while HAL locked\n");
        return -EPERM;
    }
    rc = comp_create_locked(name, realtime_host ? HAL_COMP_RT : HAL_COMP_USER, 0);
    hal_priv_unlock();
    return rc;
}

static hal_comp_t *comp_or_err(int comp_id, const char *what)
{
    hal_comp_t *c = halpr_find_comp_by_id(comp_id);
    if (c == NULL)
        ERR("HAL: ERROR: %s: component %d not found\n", what, comp_id);
    return c;
}

int hal_ready(int comp_id)
{
    if (hal_hdr == NULL)
        return -EINVAL;
    hal_priv_lock();
    hal_comp_t *c = comp_or_err(comp_id, "hal_ready");
    if (c == NULL) {
        hal_priv_unlock();
        return -EINVAL;
    }
    if (c->ready) {
        hal_priv_unlock();
        ERR("HAL: ERROR: Component '%s' already ready\n", c->name);
        return -EINVAL;
    }
    c->ready = 1;
    hal_priv_unlock();
    return 0;
}

int hal_unready(int comp_id)
{
    if (hal_hdr == NULL)
        return -EINVAL;
    hal_priv_lock();
    hal_comp_t *c = comp_or_err(comp_id, "hal_unready");
    if (c == NULL) {
        hal_priv_unlock();
        return -EINVAL;
    }
    c->ready = 0;
    hal_priv_unlock();
    return 0;
}

const char *hal_comp_name(int comp_id)
{
    if (hal_hdr == NULL)
        return NULL;
    hal_priv_lock();
    hal_comp_t *c = halpr_find_comp_by_id(comp_id);
    hal_priv_unlock();
    return c ? c->name : NULL;
}

/* ---- signals --------------------------------------------------------------- */

static void set_pin_ptr(hal_pin_t *pin, hal_data_u *target)
{
    hal_comp_t *owner = SHMPTR(pin->owner);
    /* The pointer is written as the owner process sees the segment. */
    uint64_t val = owner->shmem_base + (uint64_t)((char *)target - hal_shmem_base);
    void **pp = SHMPTR(pin->data_ptr_addr);
    *pp = (void *)(uintptr_t)val;
}

static void unlink_pin_locked(hal_pin_t *pin)
{
    if (pin->signal == 0)
        return;
    hal_sig_t *sig = SHMPTR(pin->signal);
    /* The pin keeps the signal's last value (LinuxCNC 2.9). */
    pin->dummysig = *halpr_sig_value(sig);
    set_pin_ptr(pin, &pin->dummysig);
    pin->signal = 0;
    if (pin->dir == HAL_OUT)
        sig->writers--;
    else if (pin->dir == HAL_IO)
        sig->bidirs--;
    else
        sig->readers--;
}

static int valid_type(int type)
{
    return type == HAL_BIT || type == HAL_FLOAT || type == HAL_S32 || type == HAL_U32 ||
           type == HAL_S64 || type == HAL_U64;
}

int hal_signal_new(const char *name, hal_type_t type)
{
    int rc = check_name("signal", name);
    if (rc)
        return rc;
    if (!valid_type(type)) {
        ERR("HAL: ERROR: signal '%s': bad type %d\n", name, (int)type);
        return -EINVAL;
    }
    if ((rc = hal_priv_attach()))
        return rc;
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        hal_priv_unlock();
        ERR("HAL: ERROR: signal_new called while HAL is locked\n");
        return -EPERM;
    }
    if (halpr_find_sig_by_name(name) != NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: duplicate signal '%s'\n", name);
        return -EEXIST;
    }
    hal_sig_t *sig = alloc_obj(sizeof(hal_sig_t) + sizeof(hal_data_u) + 8, &hal_hdr->sig_free,
                               &hal_hdr->recycled_sigs);
    if (sig == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: insufficient memory for signal '%s'\n", name);
        return -ENOMEM;
    }
    /* The value lives right behind the record, 8-aligned, so it is
     * recycled with it. */
    hal_off_t data = (SHMOFF(sig) + (hal_off_t)sizeof(hal_sig_t) + 7u) & ~7u;
    sig->data_ptr = data;
    memset(SHMPTR(data), 0, sizeof(hal_data_u));
    sig->type = type;
    snprintf(sig->name, sizeof(sig->name), "%s", name);
    list_insert_sorted(HAL_IDX_SIG, sig);
    hal_hdr->active_sigs++;
    hal_priv_unlock();
    return 0;
}

int hal_signal_delete(const char *name)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        hal_priv_unlock();
        ERR("HAL: ERROR: signal_delete called while HAL locked\n");
        return -EPERM;
    }
    hal_sig_t *sig = halpr_find_sig_by_name(name);
    if (sig == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: signal '%s' not found\n", name);
        return -EINVAL;
    }
    for (hal_off_t off = hal_hdr->pin_list; off != 0;) {
        hal_pin_t *p = SHMPTR(off);
        if (p->signal == SHMOFF(sig))
            unlink_pin_locked(p);
        off = p->next;
    }
    list_remove(HAL_IDX_SIG, sig);
    free_obj(sig, &hal_hdr->sig_free, &hal_hdr->recycled_sigs);
    hal_hdr->active_sigs--;
    hal_priv_unlock();
    return 0;
}

/* The checks of hal_link, shared with halcmd's net dry run. */
int halpr_check_link(hal_pin_t *pin, hal_sig_t *sig, int writers, int bidirs, int quiet)
{
    if (pin->signal != 0 && pin->signal != SHMOFF(sig)) {
        if (!quiet)
            ERR("HAL: ERROR: pin '%s' is linked to '%s', cannot link to '%s'\n", pin->name,
                ((hal_sig_t *)SHMPTR(pin->signal))->name, sig->name);
        return -EINVAL;
    }
    if (pin->type != sig->type) {
        if (!quiet)
            ERR("HAL: ERROR: type mismatch '%s' <- '%s'\n", pin->name, sig->name);
        return -EINVAL;
    }
    if (pin->signal == SHMOFF(sig))
        return 0;
    if (pin->dir == HAL_OUT && (writers > 0 || bidirs > 0)) {
        if (!quiet)
            ERR("HAL: ERROR: signal '%s' already has output or I/O pin(s)\n", sig->name);
        return -EINVAL;
    }
    if (pin->dir == HAL_IO && writers > 0) {
        if (!quiet)
            ERR("HAL: ERROR: signal '%s' already has output pin\n", sig->name);
        return -EINVAL;
    }
    return 0;
}

static void link_locked(hal_pin_t *pin, hal_sig_t *sig)
{
    if (pin->signal == SHMOFF(sig))
        return;
    /* The seeds' rule: an OUT pin's old value is never copied into the
     * signal.  LinuxCNC 2.9 seeds a signal that has no pin yet from its
     * first IN/IO pin; that costs the seeds' rule nothing, so we do too. */
    if (pin->dir != HAL_OUT && sig->readers == 0 && sig->writers == 0 && sig->bidirs == 0)
        *halpr_sig_value(sig) = pin->dummysig;
    pin->signal = SHMOFF(sig);
    set_pin_ptr(pin, halpr_sig_value(sig));
    if (pin->dir == HAL_OUT)
        sig->writers++;
    else if (pin->dir == HAL_IO)
        sig->bidirs++;
    else
        sig->readers++;
}

int hal_link(const char *pin_name, const char *sig_name)
{
    if (pin_name == NULL || sig_name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        hal_priv_unlock();
        ERR("HAL: ERROR: link called while HAL locked\n");
        return -EPERM;
    }
    hal_sig_t *sig = halpr_find_sig_by_name(sig_name);
    if (sig == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: signal '%s' not found\n", sig_name);
        return -EINVAL;
    }
    hal_pin_t *pin = halpr_find_pin_by_name(pin_name);
    if (pin == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: pin '%s' not found\n", pin_name);
        return -EINVAL;
    }
    int rc = halpr_check_link(pin, sig, sig->writers, sig->bidirs, 0);
    if (rc == 0)
        link_locked(pin, sig);
    hal_priv_unlock();
    return rc;
}

int hal_unlink(const char *pin_name)
{
    if (pin_name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        hal_priv_unlock();
        ERR("HAL: ERROR: unlink called while HAL locked\n");
        return -EPERM;
    }
    hal_pin_t *pin = halpr_find_pin_by_name(pin_name);
    if (pin == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: pin '%s' not found\n", pin_name);
        return -EINVAL;
    }
    unlink_pin_locked(pin);
    hal_priv_unlock();
    return 0;
}

/* ---- pins ------------------------------------------------------------------ */

static hal_comp_t *comp_for_new_object(int comp_id, const char *what, const char *name)
{
    hal_comp_t *c = halpr_find_comp_by_id(comp_id);
    if (c == NULL) {
        ERR("HAL: ERROR: %s '%s': component %d not found\n", what, name, comp_id);
        return NULL;
    }
    if (c->ready) {
        ERR("HAL: ERROR: %s_new called after hal_ready ('%s')\n", what, name);
        return NULL;
    }
    return c;
}

static int pin_new_locked(const char *name, hal_type_t type, hal_pin_dir_t dir,
                          void **data_ptr_addr, int comp_id)
{
    if (hal_hdr->lock & HAL_LOCK_LOAD) {
        ERR("HAL: ERROR: pin_new called while HAL locked\n");
        return -EPERM;
    }
    hal_comp_t *c = comp_for_new_object(comp_id, "pin", name);
    if (c == NULL)
        return -EINVAL;
    if (name_in_use_pin(name)) {
        ERR("HAL: ERROR: duplicate variable '%s'\n", name);
        return -EEXIST;
    }
    hal_pin_t *pin = alloc_obj(sizeof(hal_pin_t), &hal_hdr->pin_free, &hal_hdr->recycled_pins);
    if (pin == NULL) {
        ERR("HAL: ERROR: insufficient memory for pin '%s'\n", name);
        return -ENOMEM;
    }
    pin->data_ptr_addr = SHMOFF(data_ptr_addr);
    pin->owner = SHMOFF(c);
    pin->type = type;
    pin->dir = dir;
    snprintf(pin->name, sizeof(pin->name), "%s", name);
    set_pin_ptr(pin, &pin->dummysig);
    list_insert_sorted(HAL_IDX_PIN, pin);
    hal_hdr->active_pins++;
    return 0;
}

int hal_pin_new(const char *name, hal_type_t type, hal_pin_dir_t dir, void **data_ptr_addr,
                int comp_id)
{
    int rc = check_name("pin", name);
    if (rc)
        return rc;
    if (!valid_type(type)) {
        ERR("HAL: ERROR: pin '%s': bad type %d\n", name, (int)type);
        return -EINVAL;
    }
    if (dir != HAL_IN && dir != HAL_OUT && dir != HAL_IO) {
        ERR("HAL: ERROR: pin '%s': bad direction %d\n", name, (int)dir);
        return -EINVAL;
    }
    if (hal_hdr == NULL) {
        ERR("HAL: ERROR: pin '%s': hal_init was not called\n", name);
        return -EINVAL;
    }
    if (!SHMCHK(data_ptr_addr)) {
        ERR("HAL: ERROR: pin '%s': data_ptr_addr not in shared memory\n", name);
        return -EINVAL;
    }
    hal_priv_lock();
    rc = pin_new_locked(name, type, dir, data_ptr_addr, comp_id);
    hal_priv_unlock();
    return rc;
}

#define PIN_NEW_TYPED(fn, htype, ctype)                                                 \
    int fn(const char *name, hal_pin_dir_t dir, ctype **data_ptr_addr, int comp_id)     \
    {                                                                                   \
        return hal_pin_new(name, htype, dir, (void **)data_ptr_addr, comp_id);          \
    }
PIN_NEW_TYPED(hal_pin_bit_new, HAL_BIT, hal_bit_t)
PIN_NEW_TYPED(hal_pin_float_new, HAL_FLOAT, hal_float_t)
PIN_NEW_TYPED(hal_pin_u32_new, HAL_U32, hal_u32_t)
PIN_NEW_TYPED(hal_pin_s32_new, HAL_S32, hal_s32_t)
PIN_NEW_TYPED(hal_pin_u64_new, HAL_U64, hal_u64_t)
PIN_NEW_TYPED(hal_pin_s64_new, HAL_S64, hal_s64_t)

static int vformat_name(char *buf, const char *what, const char *fmt, va_list ap)
{
    int n = vsnprintf(buf, HAL_NAME_LEN + 1, fmt, ap);
    if (n < 0 || n > HAL_NAME_LEN) {
        ERR("HAL: ERROR: %s name '%s...' is too long\n", what, buf);
        return -ENOMEM;
    }
    return 0;
}

#define PIN_NEWF_TYPED(fn, htype, ctype)                                                   \
    int fn(hal_pin_dir_t dir, ctype **data_ptr_addr, int comp_id, const char *fmt, ...)    \
    {                                                                                      \
        char name[HAL_NAME_LEN + 1];                                                       \
        va_list ap;                                                                        \
        va_start(ap, fmt);                                                                 \
        int rc = vformat_name(name, "pin", fmt, ap);                                       \
        va_end(ap);                                                                        \
        if (rc)                                                                            \
            return rc;                                                                     \
        return hal_pin_new(name, htype, dir, (void **)data_ptr_addr, comp_id);             \
    }
PIN_NEWF_TYPED(hal_pin_bit_newf, HAL_BIT, hal_bit_t)
PIN_NEWF_TYPED(hal_pin_float_newf, HAL_FLOAT, hal_float_t)
PIN_NEWF_TYPED(hal_pin_u32_newf, HAL_U32, hal_u32_t)
PIN_NEWF_TYPED(hal_pin_s32_newf, HAL_S32, hal_s32_t)
PIN_NEWF_TYPED(hal_pin_u64_newf, HAL_U64, hal_u64_t)
PIN_NEWF_TYPED(hal_pin_s64_newf, HAL_S64, hal_s64_t)

int hal_pin_newf(hal_type_t type, hal_pin_dir_t dir, void **data_ptr_addr, int comp_id,
                 const char *fmt, ...)
{
    char name[HAL_NAME_LEN + 1];
    va_list ap;
    va_start(ap, fmt);
    int rc = vformat_name(name, "pin", fmt, ap);
    va_end(ap);
    if (rc)
        return rc;
    return hal_pin_new(name, type, dir, data_ptr_addr, comp_id);
}

/* ---- aliases --------------------------------------------------------------- */

static int alias_common(int is_pin, const char *orig, const char *alias)
{
    const char *what = is_pin ? "pin" : "param";
    if (orig == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    if (alias != NULL && alias[0] != '\0' && strlen(alias) > HAL_NAME_LEN) {
        ERR("HAL: ERROR: alias name '%s' is too long\n", alias);
        return -EINVAL;
    }
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        hal_priv_unlock();
        ERR("HAL: ERROR: %s_alias called while HAL locked\n", what);
        return -EPERM;
    }
    void *obj;
    hal_off_t *oldname;
    char *namefield;
    int kind = is_pin ? HAL_IDX_PIN : HAL_IDX_PARAM;
    if (is_pin) {
        hal_pin_t *p = halpr_find_pin_by_name(orig);
        obj = p;
        if (p) {
            oldname = &p->oldname;
            namefield = p->name;
        }
    } else {
        hal_param_t *p = halpr_find_param_by_name(orig);
        obj = p;
        if (p) {
            oldname = &p->oldname;
            namefield = p->name;
        }
    }
    if (obj == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: %s '%s' not found\n", what, orig);
        return -EINVAL;
    }
    if (alias != NULL && alias[0] != '\0') {
        void *other = is_pin ? (void *)halpr_find_pin_by_name(alias)
                             : (void *)halpr_find_param_by_name(alias);
        if (other != NULL && other != obj) {
            hal_priv_unlock();
            ERR("HAL: ERROR: duplicate %s or alias name '%s'\n", what, alias);
            return -EINVAL;
        }
        if (*oldname == 0) {
            hal_oldname_t *on = alloc_obj(sizeof(hal_oldname_t), &hal_hdr->oldname_free,
                                          &hal_hdr->recycled_aliases);
            if (on == NULL) {
                hal_priv_unlock();
                ERR("HAL: ERROR: insufficient memory for alias '%s'\n", alias);
                return -ENOMEM;
            }
            snprintf(on->name, sizeof(on->name), "%s", namefield);
            *oldname = SHMOFF(on);
            hal_hdr->active_aliases++;
        }
        list_remove(kind, obj);
        snprintf(namefield, HAL_NAME_LEN + 1, "%s", alias);
        list_insert_sorted(kind, obj);
    } else if (*oldname != 0) {
        hal_oldname_t *on = SHMPTR(*oldname);
        list_remove(kind, obj);
        snprintf(namefield, HAL_NAME_LEN + 1, "%s", on->name);
        list_insert_sorted(kind, obj);
        *oldname = 0;
        free_obj(on, &hal_hdr->oldname_free, &hal_hdr->recycled_aliases);
        hal_hdr->active_aliases--;
    }
    hal_priv_unlock();
    return 0;
}

int hal_pin_alias(const char *pin_name, const char *alias)
{
    return alias_common(1, pin_name, alias);
}

int hal_param_alias(const char *param_name, const char *alias)
{
    return alias_common(0, param_name, alias);
}

/* ---- parameters ------------------------------------------------------------ */

static int param_new_locked(const char *name, hal_type_t type, hal_param_dir_t dir,
                            volatile void *data_addr, int comp_id)
{
    if (hal_hdr->lock & HAL_LOCK_LOAD) {
        ERR("HAL: ERROR: param_new called while HAL locked\n");
        return -EPERM;
    }
    hal_comp_t *c = comp_for_new_object(comp_id, "param", name);
    if (c == NULL)
        return -EINVAL;
    if (halpr_find_param_by_name(name) != NULL) {
        ERR("HAL: ERROR: duplicate parameter '%s'\n", name);
        return -EEXIST;
    }
    hal_param_t *p =
        alloc_obj(sizeof(hal_param_t), &hal_hdr->param_free, &hal_hdr->recycled_params);
    if (p == NULL) {
        ERR("HAL: ERROR: insufficient memory for parameter '%s'\n", name);
        return -ENOMEM;
    }
    p->data_ptr = SHMOFF(data_addr);
    p->owner = SHMOFF(c);
    p->type = type;
    p->dir = dir;
    snprintf(p->name, sizeof(p->name), "%s", name);
    list_insert_sorted(HAL_IDX_PARAM, p);
    hal_hdr->active_params++;
    return 0;
}

int hal_param_new(const char *name, hal_type_t type, hal_param_dir_t dir,
                  volatile void *data_addr, int comp_id)
{
    int rc = check_name("parameter", name);
    if (rc)
        return rc;
    if (!valid_type(type)) {
        ERR("HAL: ERROR: parameter '%s': bad type %d\n", name, (int)type);
        return -EINVAL;
    }
    if (dir != HAL_RO && dir != HAL_RW) {
        ERR("HAL: ERROR: parameter '%s': bad direction %d\n", name, (int)dir);
        return -EINVAL;
    }
    if (hal_hdr == NULL) {
        ERR("HAL: ERROR: parameter '%s': hal_init was not called\n", name);
        return -EINVAL;
    }
    if (!SHMCHK(data_addr)) {
        ERR("HAL: ERROR: parameter '%s': data_addr not in shared memory\n", name);
        return -EINVAL;
    }
    hal_priv_lock();
    rc = param_new_locked(name, type, dir, data_addr, comp_id);
    hal_priv_unlock();
    return rc;
}

#define PARAM_NEW_TYPED(fn, htype, ctype)                                            \
    int fn(const char *name, hal_param_dir_t dir, ctype *data_addr, int comp_id)     \
    {                                                                                \
        return hal_param_new(name, htype, dir, data_addr, comp_id);                  \
    }
PARAM_NEW_TYPED(hal_param_bit_new, HAL_BIT, hal_bit_t)
PARAM_NEW_TYPED(hal_param_float_new, HAL_FLOAT, hal_float_t)
PARAM_NEW_TYPED(hal_param_u32_new, HAL_U32, hal_u32_t)
PARAM_NEW_TYPED(hal_param_s32_new, HAL_S32, hal_s32_t)
PARAM_NEW_TYPED(hal_param_u64_new, HAL_U64, hal_u64_t)
PARAM_NEW_TYPED(hal_param_s64_new, HAL_S64, hal_s64_t)

#define PARAM_NEWF_TYPED(fn, htype, ctype)                                               \
    int fn(hal_param_dir_t dir, ctype *data_addr, int comp_id, const char *fmt, ...)     \
    {                                                                                    \
        char name[HAL_NAME_LEN + 1];                                                     \
        va_list ap;                                                                      \
        va_start(ap, fmt);                                                               \
        int rc = vformat_name(name, "parameter", fmt, ap);                               \
        va_end(ap);                                                                      \
        if (rc)                                                                          \
            return rc;                                                                   \
        return hal_param_new(name, htype, dir, data_addr, comp_id);                      \
    }
PARAM_NEWF_TYPED(hal_param_bit_newf, HAL_BIT, hal_bit_t)
PARAM_NEWF_TYPED(hal_param_float_newf, HAL_FLOAT, hal_float_t)
PARAM_NEWF_TYPED(hal_param_u32_newf, HAL_U32, hal_u32_t)
PARAM_NEWF_TYPED(hal_param_s32_newf, HAL_S32, hal_s32_t)
PARAM_NEWF_TYPED(hal_param_u64_newf, HAL_U64, hal_u64_t)
PARAM_NEWF_TYPED(hal_param_s64_newf, HAL_S64, hal_s64_t)

int hal_param_newf(hal_type_t type, hal_param_dir_t dir, volatile void *data_addr, int comp_id,
                   const char *fmt, ...)
{
    char name[HAL_NAME_LEN + 1];
    va_list ap;
    va_start(ap, fmt);
    int rc = vformat_name(name, "parameter", fmt, ap);
    va_end(ap);
    if (rc)
        return rc;
    return hal_param_new(name, type, dir, data_addr, comp_id);
}

int hal_param_set(const char *name, hal_type_t type, void *value_addr)
{
    if (name == NULL || value_addr == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_PARAMS) {
        hal_priv_unlock();
        ERR("HAL: ERROR: param_set called while HAL locked\n");
        return -EPERM;
    }
    hal_param_t *p = halpr_find_param_by_name(name);
    if (p == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: parameter '%s' not found\n", name);
        return -EINVAL;
    }
    if (p->type != (int)type) {
        hal_priv_unlock();
        ERR("HAL: ERROR: type mismatch setting param '%s'\n", name);
        return -EINVAL;
    }
    if (p->dir == HAL_RO) {
        hal_priv_unlock();
        ERR("HAL: ERROR: param '%s' is not writable\n", name);
        return -EINVAL;
    }
    void *d = halpr_param_value(p);
    switch (type) {
    case HAL_BIT: *(hal_bit_t *)d = (*(int *)value_addr != 0); break;
    case HAL_FLOAT: *(hal_float_t *)d = *(double *)value_addr; break;
    case HAL_S32: *(hal_s32_t *)d = *(rtapi_s32 *)value_addr; break;
    case HAL_U32: *(hal_u32_t *)d = *(rtapi_u32 *)value_addr; break;
    case HAL_S64: *(hal_s64_t *)d = *(rtapi_s64 *)value_addr; break;
    case HAL_U64: *(hal_u64_t *)d = *(rtapi_u64 *)value_addr; break;
    default: break;
    }
    hal_priv_unlock();
    return 0;
}

int hal_param_bit_set(const char *name, int value)
{
    return hal_param_set(name, HAL_BIT, &value);
}

int hal_param_float_set(const char *name, double value)
{
    return hal_param_set(name, HAL_FLOAT, &value);
}

int hal_param_u32_set(const char *name, unsigned long value)
{
    if (value > UINT32_MAX) {
        ERR("HAL: ERROR: value %lu out of range for u32 parameter '%s'\n", value, name);
        return -EINVAL;
    }
    rtapi_u32 v = (rtapi_u32)value;
    return hal_param_set(name, HAL_U32, &v);
}

int hal_param_s32_set(const char *name, signed long value)
{
    if (value > INT32_MAX || value < INT32_MIN) {
        ERR("HAL: ERROR: value %ld out of range for s32 parameter '%s'\n", value, name);
        return -EINVAL;
    }
    rtapi_s32 v = (rtapi_s32)value;
    return hal_param_set(name, HAL_S32, &v);
}

/* ---- removal of a component and what it owns ------------------------------ */

static void funct_delete_locked(hal_funct_t *f)
{
    /* Take it out of every thread first. */
    for (hal_off_t toff = hal_hdr->thread_list; toff != 0;) {
        hal_thread_t *t = SHMPTR(toff);
        hal_off_t *prev = &t->funct_list;
        while (*prev != 0) {
            hal_funct_entry_t *e = SHMPTR(*prev);
            if (e->funct == SHMOFF(f)) {
                *prev = e->next;
                free_obj(e, &hal_hdr->funct_entry_free, NULL);
                __atomic_add_fetch(&t->gen, 1, __ATOMIC_RELEASE);
            } else {
                prev = &e->next;
            }
        }
        toff = t->next;
    }
    list_remove(HAL_IDX_FUNCT, f);
    free_obj(f, &hal_hdr->funct_free, &hal_hdr->recycled_functs);
    hal_hdr->active_functs--;
}

static void comp_delete_locked(hal_comp_t *c)
{
    hal_off_t coff = SHMOFF(c);
    hal_off_t *prev = &hal_hdr->funct_list;
    while (*prev != 0) {
        hal_funct_t *f = SHMPTR(*prev);
        if (f->owner == coff)
            funct_delete_locked(f); /* updates *prev */
        else
            prev = &f->next;
    }
    prev = &hal_hdr->pin_list;
    while (*prev != 0) {
        hal_pin_t *p = SHMPTR(*prev);
        if (p->owner == coff) {
            unlink_pin_locked(p);
            list_remove_at(HAL_IDX_PIN, prev, p);
            if (p->oldname != 0) {
                free_obj(SHMPTR(p->oldname), &hal_hdr->oldname_free, &hal_hdr->recycled_aliases);
                hal_hdr->active_aliases--;
            }
            free_obj(p, &hal_hdr->pin_free, &hal_hdr->recycled_pins);
            hal_hdr->active_pins--;
        } else {
            prev = &p->next;
        }
    }
    prev = &hal_hdr->param_list;
    while (*prev != 0) {
        hal_param_t *p = SHMPTR(*prev);
        if (p->owner == coff) {
            list_remove_at(HAL_IDX_PARAM, prev, p);
            if (p->oldname != 0) {
                free_obj(SHMPTR(p->oldname), &hal_hdr->oldname_free, &hal_hdr->recycled_aliases);
                hal_hdr->active_aliases--;
            }
            free_obj(p, &hal_hdr->param_free, &hal_hdr->recycled_params);
            hal_hdr->active_params--;
        } else {
            prev = &p->next;
        }
    }
    list_remove(HAL_IDX_COMP, c);
    free_obj(c, &hal_hdr->comp_free, &hal_hdr->recycled_comps);
    hal_hdr->active_comps--;
}

int halpr_comp_delete(int comp_id)
{
    hal_priv_lock();
    hal_comp_t *c = halpr_find_comp_by_id(comp_id);
    if (c == NULL) {
        hal_priv_unlock();
        return -EINVAL;
    }
    comp_delete_locked(c);
    hal_priv_unlock();
    return 0;
}

int hal_exit(int comp_id)
{
    if (hal_hdr == NULL) {
        ERR("HAL: ERROR: hal_exit: component %d not found\n", comp_id);
        return -EINVAL;
    }
    hal_priv_lock();
    hal_comp_t *c = halpr_find_comp_by_id(comp_id);
    if (c == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: hal_exit: component %d not found\n", comp_id);
        return -EINVAL;
    }
    comp_delete_locked(c);
    hal_priv_unlock();
    return 0;
}

int halpr_set_insmod_args(const char *name, const char *args)
{
    hal_priv_lock();
    hal_comp_t *c = halpr_find_comp_by_name(name);
    if (c == NULL) {
        hal_priv_unlock();
        return -ENOENT;
    }
    c->loaded_by_loadrt = 1;
    if (c->insmod_args == 0) {
        char *s = shmalloc_dn(HAL_ARGS_LEN);
        if (s == NULL) {
            hal_priv_unlock();
            return -ENOMEM;
        }
        c->insmod_args = SHMOFF(s);
    }
    snprintf(SHMPTR(c->insmod_args), HAL_ARGS_LEN, "%s", args);
    hal_priv_unlock();
    return 0;
}

/* ---- functions ------------------------------------------------------------- */

int hal_export_funct(const char *name, void (*funct)(void *, long), void *arg, int uses_fp,
                     int reentrant, int comp_id)
{
    int rc = check_name("function", name);
    if (rc)
        return rc;
    if (strlen(name) + strlen(".tmax-increased") > HAL_NAME_LEN) {
        ERR("HAL: ERROR: function name '%s' is too long\n", name);
        return -EINVAL;
    }
    if (hal_hdr == NULL || funct == NULL) {
        ERR("HAL: ERROR: export_funct '%s': bad arguments or no hal_init\n", name);
        return -EINVAL;
    }
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_LOAD) {
        hal_priv_unlock();
        ERR("HAL: ERROR: export_funct called while HAL locked\n");
        return -EPERM;
    }
    hal_comp_t *c = halpr_find_comp_by_id(comp_id);
    if (c == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: export_funct '%s': component %d not found\n", name, comp_id);
        return -EINVAL;
    }
    if (c->type != HAL_COMP_RT) {
        hal_priv_unlock();
        ERR("HAL: ERROR: component %d is not realtime (%d)\n", comp_id, c->type);
        return -EINVAL;
    }
    if (c->ready) {
        hal_priv_unlock();
        ERR("HAL: ERROR: export_funct called after hal_ready ('%s')\n", name);
        return -EINVAL;
    }
    char pname[HAL_NAME_LEN + 1], tname[HAL_NAME_LEN + 1], iname[HAL_NAME_LEN + 1];
    snprintf(pname, sizeof(pname), "%s.time", name);
    snprintf(tname, sizeof(tname), "%s.tmax", name);
    snprintf(iname, sizeof(iname), "%s.tmax-increased", name);
    if (halpr_find_funct_by_name(name) != NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: duplicate function '%s'\n", name);
        return -EEXIST;
    }
    if (halpr_find_pin_by_name(pname) != NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: duplicate variable '%s'\n", pname);
        return -EEXIST;
    }
    if (halpr_find_param_by_name(tname) != NULL || halpr_find_param_by_name(iname) != NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: duplicate parameter '%s'\n", tname);
        return -EEXIST;
    }
    /* Storage: the pointer of the .time pin, tmax, tmax-increased. */
    struct fstore {
        hal_s32_t *runtime;
        hal_s32_t maxtime;
        hal_bit_t maxtime_increased;
    } *st = shmalloc_dn(sizeof(struct fstore));
    hal_funct_t *f = st ? alloc_obj(sizeof(hal_funct_t), &hal_hdr->funct_free,
                                    &hal_hdr->recycled_functs)
                        : NULL;
    if (f == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: insufficient memory for function '%s'\n", name);
        return -ENOMEM;
    }
    f->owner = SHMOFF(c);
    f->uses_fp = uses_fp;
    f->reentrant = reentrant;
    f->funct = (uint64_t)(uintptr_t)funct;
    f->arg = (uint64_t)(uintptr_t)arg;
    f->runtime = SHMOFF(&st->runtime);
    f->maxtime = SHMOFF(&st->maxtime);
    f->maxtime_increased = SHMOFF(&st->maxtime_increased);
    snprintf(f->name, sizeof(f->name), "%s", name);
    list_insert_sorted(HAL_IDX_FUNCT, f);
    hal_hdr->active_functs++;
    /* Cannot fail now: names were checked, memory is all that is left. */
    rc = pin_new_locked(pname, HAL_S32, HAL_OUT, (void **)&st->runtime, comp_id);
    if (rc == 0)
        rc = param_new_locked(tname, HAL_S32, HAL_RW, &st->maxtime, comp_id);
    if (rc == 0)
        rc = param_new_locked(iname, HAL_BIT, HAL_RO, &st->maxtime_increased, comp_id);
    hal_priv_unlock();
    return rc;
}

int hal_export_functf(void (*funct)(void *, long), void *arg, int uses_fp, int reentrant,
                      int comp_id, const char *fmt, ...)
{
    char name[HAL_NAME_LEN + 1];
    va_list ap;
    va_start(ap, fmt);
    int rc = vformat_name(name, "function", fmt, ap);
    va_end(ap);
    if (rc)
        return rc;
    return hal_export_funct(name, funct, arg, uses_fp, reentrant, comp_id);
}

/* ---- threads --------------------------------------------------------------- */

int hal_create_thread(const char *name, unsigned long period_nsec, int uses_fp)
{
    int rc = check_name("thread", name);
    if (rc)
        return rc;
    if (strlen(name) + 7 > HAL_NAME_LEN) {
        ERR("HAL: ERROR: thread name '%s' is too long\n", name);
        return -EINVAL;
    }
    if (!realtime_host || hal_hdr == NULL || thread_hooks == NULL) {
        ERR("HAL: ERROR: thread '%s': threads can only be created in rtapi_app\n", name);
        return -EPERM;
    }
    if (period_nsec == 0 || period_nsec > 1000000000ul * 60) {
        ERR("HAL: ERROR: thread '%s': bad period %lu ns\n", name, period_nsec);
        return -EINVAL;
    }
    hal_priv_lock();
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        hal_priv_unlock();
        ERR("HAL: ERROR: create_thread called while HAL locked\n");
        return -EPERM;
    }
    char cname[HAL_NAME_LEN + 1], pname[HAL_NAME_LEN + 1], tname[HAL_NAME_LEN + 1];
    snprintf(cname, sizeof(cname), "__%s", name);
    snprintf(pname, sizeof(pname), "%s.time", name);
    snprintf(tname, sizeof(tname), "%s.tmax", name);
    if (halpr_find_thread_by_name(name) != NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: duplicate thread name %s\n", name);
        return -EEXIST;
    }
    if (halpr_find_comp_by_name(cname) || halpr_find_pin_by_name(pname) ||
        halpr_find_param_by_name(tname)) {
        hal_priv_unlock();
        ERR("HAL: ERROR: thread '%s': name in use by another HAL object\n", name);
        return -EEXIST;
    }
    long period = (long)period_nsec;
    if (hal_hdr->thread_list == 0) {
        hal_hdr->clock_period = period;
    } else if (period < hal_hdr->clock_period) {
        hal_priv_unlock();
        ERR("HAL_LIB: ERROR: new thread period %ld is less than clock period %ld\n", period,
            hal_hdr->clock_period);
        return -EINVAL;
    } else {
        long n = (period + hal_hdr->clock_period / 2) / hal_hdr->clock_period;
        period = n * hal_hdr->clock_period;
    }
    struct tstore {
        hal_s32_t *runtime;
        hal_s32_t maxtime;
    } *st = shmalloc_dn(sizeof(struct tstore));
    hal_thread_t *t = st ? alloc_obj(sizeof(hal_thread_t), &hal_hdr->thread_free,
                                     &hal_hdr->recycled_threads)
                         : NULL;
    if (t == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: insufficient memory to create thread '%s'\n", name);
        return -ENOMEM;
    }
    int comp_id = comp_create_locked(cname, HAL_COMP_RT, 0);
    if (comp_id < 0) {
        free_obj(t, &hal_hdr->thread_free, &hal_hdr->recycled_threads);
        hal_priv_unlock();
        return comp_id;
    }
    t->uses_fp = uses_fp;
    t->comp_id = comp_id;
    t->period = period;
    t->priority = hal_hdr->next_priority++;
    t->runtime = SHMOFF(&st->runtime);
    t->maxtime = SHMOFF(&st->maxtime);
    snprintf(t->name, sizeof(t->name), "%s", name);
    rc = pin_new_locked(pname, HAL_S32, HAL_OUT, (void **)&st->runtime, comp_id);
    if (rc == 0)
        rc = param_new_locked(tname, HAL_S32, HAL_RW, &st->maxtime, comp_id);
    if (rc == 0) {
        halpr_find_comp_by_id(comp_id)->ready = 1;
        list_insert_front(HAL_IDX_THREAD, t); /* newest (slowest) first */
        hal_hdr->active_threads++;
        rc = thread_hooks->thread_created(t);
        if (rc != 0) {
            list_remove(HAL_IDX_THREAD, t);
            hal_hdr->active_threads--;
        }
    }
    if (rc != 0) {
        comp_delete_locked(halpr_find_comp_by_id(comp_id));
        free_obj(t, &hal_hdr->thread_free, &hal_hdr->recycled_threads);
        if (hal_hdr->thread_list == 0)
            hal_hdr->clock_period = 0;
        hal_priv_unlock();
        ERR("HAL: ERROR: could not start thread '%s' (%d)\n", name, rc);
        return rc;
    }
    hal_priv_unlock();
    return 0;
}

int hal_thread_delete(const char *name)
{
    if (name == NULL || hal_hdr == NULL)
        return -EINVAL;
    /* Like hal_exit, allowed while locked: a session must be able to end. */
    hal_priv_lock();
    hal_thread_t *t = halpr_find_thread_by_name(name);
    if (t == NULL) {
        hal_priv_unlock();
        ERR("HAL: ERROR: thread '%s' not found\n", name);
        return -EINVAL;
    }
    hal_priv_unlock();
    /* Stop the OS thread without the lock held (it may need the lock to
     * pick up a changed function list). */
    if (thread_hooks != NULL)
        thread_hooks->thread_deleting(t);
    hal_priv_lock();
    while (t->funct_list != 0) {
        hal_funct_entry_t *e = SHMPTR(t->funct_list);
        hal_funct_t *f = SHMPTR(e->funct);
        f->users--;
        t->funct_list = e->next;
        free_obj(e, &hal_hdr->funct_entry_free, NULL);
    }
    hal_comp_t *c = halpr_find_comp_by_id(t->comp_id);
    if (c != NULL)
        comp_delete_locked(c);
    list_remove(HAL_IDX_THREAD, t);
    free_obj(t, &hal_hdr->thread_free, &hal_hdr->recycled_threads);
    hal_hdr->active_threads--;
    if (hal_hdr->thread_list == 0)
        hal_hdr->clock_period = 0;
    hal_priv_unlock();
    return 0;
}

int hal_add_funct_to_thread(const char *funct_name, const char *thread_name, int position)
{
    if (funct_name == NULL || thread_name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    int rc = -EINVAL;
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        ERR("HAL: ERROR: add_funct_to_thread called while HAL is locked\n");
        rc = -EPERM;
        goto out;
    }
    if (position == 0) {
        ERR("HAL: ERROR: bad position: 0\n");
        goto out;
    }
    hal_funct_t *f = halpr_find_funct_by_name(funct_name);
    if (f == NULL) {
        ERR("HAL: ERROR: function '%s' not found\n", funct_name);
        goto out;
    }
    if (f->users > 0 && !f->reentrant) {
        ERR("HAL: ERROR: function '%s' may only be added to one thread\n", funct_name);
        goto out;
    }
    hal_thread_t *t = halpr_find_thread_by_name(thread_name);
    if (t == NULL) {
        ERR("HAL: ERROR: thread '%s' not found\n", thread_name);
        goto out;
    }
    if (f->uses_fp && !t->uses_fp) {
        ERR("HAL: ERROR: function '%s' needs FP\n", funct_name);
        goto out;
    }
    int n = 0;
    for (hal_off_t off = t->funct_list; off != 0; off = ((hal_funct_entry_t *)SHMPTR(off))->next)
        n++;
    int index; /* insert before entry `index` (0-based) */
    if (position > 0) {
        if (position > n + 1) {
            ERR("HAL: ERROR: position '%d' is too high\n", position);
            goto out;
        }
        index = position - 1;
    } else {
        if (-position > n + 1) {
            ERR("HAL: ERROR: position '%d' is too low\n", position);
            goto out;
        }
        index = n + 1 + position;
    }
    hal_funct_entry_t *e = alloc_obj(sizeof(hal_funct_entry_t), &hal_hdr->funct_entry_free, NULL);
    if (e == NULL) {
        ERR("HAL: ERROR: insufficient memory for thread function link\n");
        rc = -ENOMEM;
        goto out;
    }
    e->funct = SHMOFF(f);
    hal_off_t *prev = &t->funct_list;
    for (int i = 0; i < index; i++)
        prev = &((hal_funct_entry_t *)SHMPTR(*prev))->next;
    e->next = *prev;
    __atomic_store_n(prev, SHMOFF(e), __ATOMIC_RELEASE);
    f->users++;
    __atomic_add_fetch(&t->gen, 1, __ATOMIC_RELEASE);
    rc = 0;
out:
    hal_priv_unlock();
    return rc;
}

int hal_del_funct_from_thread(const char *funct_name, const char *thread_name)
{
    if (funct_name == NULL || thread_name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    int rc = -EINVAL;
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        ERR("HAL: ERROR: del_funct_from_thread called while HAL is locked\n");
        rc = -EPERM;
        goto out;
    }
    hal_funct_t *f = halpr_find_funct_by_name(funct_name);
    if (f == NULL) {
        ERR("HAL: ERROR: function '%s' not found\n", funct_name);
        goto out;
    }
    if (f->users == 0) {
        ERR("HAL: ERROR: function '%s' is not in use\n", funct_name);
        goto out;
    }
    hal_thread_t *t = halpr_find_thread_by_name(thread_name);
    if (t == NULL) {
        ERR("HAL: ERROR: thread '%s' not found\n", thread_name);
        goto out;
    }
    hal_off_t *prev = &t->funct_list;
    while (*prev != 0) {
        hal_funct_entry_t *e = SHMPTR(*prev);
        if (e->funct == SHMOFF(f)) {
            __atomic_store_n(prev, e->next, __ATOMIC_RELEASE);
            free_obj(e, &hal_hdr->funct_entry_free, NULL);
            f->users--;
            __atomic_add_fetch(&t->gen, 1, __ATOMIC_RELEASE);
            rc = 0;
            goto out;
        }
        prev = &e->next;
    }
    ERR("HAL: ERROR: thread '%s' doesn't use %s\n", thread_name, funct_name);
out:
    hal_priv_unlock();
    return rc;
}

int hal_start_threads(void)
{
    if (hal_priv_attach() != 0)
        return -EINVAL;
    if (hal_hdr->lock & HAL_LOCK_RUN) {
        ERR("HAL: ERROR: start_threads called while HAL is locked\n");
        return -EPERM;
    }
    hal_hdr->threads_running = 1;
    return 0;
}

int hal_stop_threads(void)
{
    if (hal_priv_attach() != 0)
        return -EINVAL;
    if (hal_hdr->lock & HAL_LOCK_RUN) {
        ERR("HAL: ERROR: stop_threads called while HAL is locked\n");
        return -EPERM;
    }
    hal_hdr->threads_running = 0;
    __atomic_add_fetch(&hal_hdr->sim_abort, 1, __ATOMIC_RELEASE);
    return 0;
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
