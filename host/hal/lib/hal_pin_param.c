/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_pin_param.c - pins, parameters and their aliases.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hal_lib_int.h"

/* ---- pins ------------------------------------------------------------------ */

hal_comp_t *comp_for_new_object(int comp_id, const char *what, const char *name)
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

int pin_new_locked(const char *name, hal_type_t type, hal_pin_dir_t dir,
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

int param_new_locked(const char *name, hal_type_t type, hal_param_dir_t dir,
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
