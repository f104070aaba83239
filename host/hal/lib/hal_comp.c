/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_comp.c - components: hal_init, ready/unready, and hal_exit, which
 * removes a component with everything it owns (functions leave their
 * threads, pins are unlinked).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_lib_int.h"

/* ---- components ------------------------------------------------------------ */

int comp_create_locked(const char *name, int type, int ready)
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
    rc = comp_create_locked(name, hal_priv_is_realtime_host() ? HAL_COMP_RT : HAL_COMP_USER, 0);
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
/* ---- removal of a component and what it owns ------------------------------ */

void funct_delete_locked(hal_funct_t *f)
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

void comp_delete_locked(hal_comp_t *c)
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

/* ---- component ids (LinuxCNC's sequence, see halcmd) ---------------------------- */

int halpr_reserve_ids(int n)
{
    if (hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    int first = hal_hdr->next_id;
    hal_hdr->next_id += n;
    hal_priv_unlock();
    return first;
}

void halpr_release_ids(int first, int n)
{
    hal_priv_lock();
    if (hal_hdr->next_id == first + n)
        hal_hdr->next_id = first;
    hal_priv_unlock();
}

int halpr_comp_set_id(int old_id, int new_id)
{
    hal_priv_lock();
    hal_comp_t *c = halpr_find_comp_by_id(old_id);
    if (c == NULL || halpr_find_comp_by_id(new_id) != NULL) {
        hal_priv_unlock();
        return -EINVAL;
    }
    hal_off_t off = SHMOFF(c);
    hal_off_t *pp = &hal_hdr->comp_list;
    while (*pp != off)
        pp = &((hal_comp_t *)SHMPTR(*pp))->next;
    *pp = c->next;
    c->id = new_id;
    /* the list is newest (highest id) first */
    pp = &hal_hdr->comp_list;
    while (*pp != 0 && ((hal_comp_t *)SHMPTR(*pp))->id > c->id)
        pp = &((hal_comp_t *)SHMPTR(*pp))->next;
    c->next = *pp;
    *pp = off;
    hal_priv_unlock();
    return 0;
}
