/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_thread.c - realtime functions (hal_export_funct with their .time /
 * .tmax storage) and threads (created in rtapi_app through its hooks),
 * addf/delf, start/stop.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_lib_int.h"

/* ---- functions ------------------------------------------------------------- */

int hal_export_funct(const char *name, void (*funct)(void *, long), void *arg, int uses_fp,
                     int reentrant, int comp_id)
{
    int rc = check_name("function", name);
    if (rc)
        return rc;
    /* NAME.time and NAME.tmax must fit; NAME.tmax-increased is cut at
     * HAL_NAME_LEN characters, as LinuxCNC 2.9 does (its sample config
     * shuttle.hal names instances tristate-float.sxp-jog-increment-0). */
    if (strlen(name) + strlen(".tmax") > HAL_NAME_LEN) {
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
    hal_funct_store_t *st = shmalloc_dn(sizeof(hal_funct_store_t));
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
    if (!hal_priv_is_realtime_host() || hal_hdr == NULL || hal_thread_hooks == NULL) {
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
        rc = hal_thread_hooks->thread_created(t);
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
    if (hal_thread_hooks != NULL)
        hal_thread_hooks->thread_deleting(t);
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

int halpr_set_exact(void)
{
    if (hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    int have_threads = hal_hdr->thread_list != 0;
    if (!have_threads)
        hal_hdr->exact_for_test = 1;
    hal_priv_unlock();
    return have_threads ? -EBUSY : 0;
}

void halpr_sim_advance(long long ns)
{
    if (hal_priv_attach() != 0)
        return;
    hal_priv_lock();
    hal_hdr->sim_time += ns;
    hal_priv_unlock();
}
