/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_signal.c - signals and the rules of linking pins to them.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_lib_int.h"

/* ---- signals --------------------------------------------------------------- */

void set_pin_ptr(hal_pin_t *pin, hal_data_u *target)
{
    hal_comp_t *owner = SHMPTR(pin->owner);
    /* The pointer is written as the owner process sees the segment. */
    uint64_t val = owner->shmem_base + (uint64_t)((char *)target - hal_shmem_base);
    void **pp = SHMPTR(pin->data_ptr_addr);
    *pp = (void *)(uintptr_t)val;
}

void unlink_pin_locked(hal_pin_t *pin)
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
