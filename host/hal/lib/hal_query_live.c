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
static const volatile void *ref_storage(const hal_q_ref_t *r)
{
    switch (r->kind) {
    case HAL_Q_PIN: {
        const hal_pin_t *p = SHMPTR(r->off);
        hal_off_t sig = __atomic_load_n(&p->signal, __ATOMIC_ACQUIRE);
        if (sig == 0)
            return &p->dummysig;
        const hal_sig_t *s = SHMPTR(sig);
        return SHMPTR(__atomic_load_n(&s->data_ptr, __ATOMIC_RELAXED));
    }
    case HAL_Q_PARAM:
        return SHMPTR(((const hal_param_t *)SHMPTR(r->off))->data_ptr);
    default:
        return SHMPTR(((const hal_sig_t *)SHMPTR(r->off))->data_ptr);
    }
}

void hal_q_ref_read(const hal_q_ref_t *refs, int n, hal_data_u *out)
{
    for (int i = 0; i < n; i++) {
        const volatile void *src = ref_storage(&refs[i]);
        hal_data_u v;
        memset(&v, 0, sizeof(v));
        switch (refs[i].type) {
        case HAL_BIT: v.b = *(const volatile hal_bit_t *)src; break;
        case HAL_FLOAT: v.f = *(const volatile hal_float_t *)src; break;
        case HAL_S32: v.s = *(const volatile hal_s32_t *)src; break;
        case HAL_U32: v.u = *(const volatile hal_u32_t *)src; break;
        case HAL_S64: v.ls = *(const volatile hal_s64_t *)src; break;
        case HAL_U64: v.lu = *(const volatile hal_u64_t *)src; break;
        default: break;
        }
        out[i] = v;
    }
}
