/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_query_live.c - what live viewers (halmeter, halscope, halshow) need
 * beyond name lookups (hal_query.h): whether a session exists without
 * creating one, and references to pin, parameter and signal values that
 * are read without the HAL mutex, for realtime readers such as scope_rt.
 * Objects are never unmapped and their storage is never freed while the
 * session lives, so a read through a reference is always a read of segment
 * memory; links are followed at the moment of the read.
 */
#include <errno.h>
#include <stdint.h>
#include <string.h>

#include "hal_priv.h"
#include "hal_query.h"

int hal_q_session_exists(void)
{
    if (hal_shmem_base != NULL)
        return 1;
    return hal_priv_session_state() == 1;
}

int hal_q_ref(hal_q_kind_t kind, const char *name, hal_q_ref_t *ref)
{
    if (name == NULL || ref == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    int rc = 0;
    hal_priv_lock();
    switch (kind) {
    case HAL_Q_PIN: {
        hal_pin_t *p = halpr_find_pin_by_name(name);
        if (p == NULL)
            rc = -ENOENT;
        else
            *ref = (hal_q_ref_t){.off = SHMOFF(p), .kind = HAL_Q_PIN, .type = p->type};
        break;
    }
    case HAL_Q_PARAM: {
        hal_param_t *p = halpr_find_param_by_name(name);
        if (p == NULL)
            rc = -ENOENT;
        else
            *ref = (hal_q_ref_t){.off = SHMOFF(p), .kind = HAL_Q_PARAM, .type = p->type};
        break;
    }
    case HAL_Q_SIG: {
        hal_sig_t *s = halpr_find_sig_by_name(name);
        if (s == NULL)
            rc = -ENOENT;
        else
            *ref = (hal_q_ref_t){.off = SHMOFF(s), .kind = HAL_Q_SIG, .type = s->type};
        break;
    }
    default: rc = -EINVAL; break;
    }
    hal_priv_unlock();
    return rc;
}

/* Where the value lives now.  Offsets are read once each (a concurrent
 * link/unlink changes them as a whole), so the result is either the old or
 * the new storage, both inside the segment. */
static inline const volatile void *ref_storage(const char *base, const hal_q_ref_t *r)
{
    switch (r->kind) {
    case HAL_Q_PIN: {
        const hal_pin_t *p = (const hal_pin_t *)(base + r->off);
        hal_off_t sig = __atomic_load_n(&p->signal, __ATOMIC_ACQUIRE);
        if (sig == 0)
            return &p->dummysig;
        const hal_sig_t *s = (const hal_sig_t *)(base + sig);
        return base + __atomic_load_n(&s->data_ptr, __ATOMIC_RELAXED);
    }
    case HAL_Q_PARAM:
        return base + ((const hal_param_t *)(base + r->off))->data_ptr;
    default:
        return base + ((const hal_sig_t *)(base + r->off))->data_ptr;
    }
}

/* The realtime scope's inner loop (bench/halview measures it): first every
 * value's current storage, then the values, one 8-byte store each, so the
 * independent loads of different channels overlap. */
void hal_q_ref_read(const hal_q_ref_t *refs, int n, hal_data_u *out)
{
    const char *base = hal_shmem_base;
    volatile uint64_t *dst = (volatile uint64_t *)out;
    const volatile void *src[64];
    for (int i0 = 0; i0 < n; i0 += 64) {
        int m = n - i0 < 64 ? n - i0 : 64;
        for (int i = 0; i < m; i++)
            src[i] = ref_storage(base, &refs[i0 + i]);
        for (int i = 0; i < m; i++) {
            uint64_t w;
            switch (refs[i0 + i].type) {
            case HAL_BIT: w = *(const volatile uint8_t *)src[i] != 0; break;
            case HAL_S32:
            case HAL_U32: w = *(const volatile uint32_t *)src[i]; break;
            case HAL_FLOAT:
            case HAL_S64:
            case HAL_U64: w = *(const volatile uint64_t *)src[i]; break;
            default: w = 0; break;
            }
            dst[i0 + i] = w;
        }
    }
}
