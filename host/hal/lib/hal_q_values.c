/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_q_values.c - values by name (hal_query.h): text <-> value with
 * halcmd's rules, and getp/setp/gets/sets with LinuxCNC halcmd's messages.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "hal_lib_int.h"
#include "hal_query.h"

#define SETERR(...)                                   \
    do {                                              \
        if (err != NULL && errlen > 0)                \
            snprintf(err, errlen, __VA_ARGS__);       \
    } while (0)

hal_type_t hal_q_type_from_name(const char *name)
{
    static const struct {
        const char *n;
        hal_type_t t;
    } tab[] = {{"bit", HAL_BIT}, {"float", HAL_FLOAT}, {"s32", HAL_S32},
               {"u32", HAL_U32}, {"s64", HAL_S64},     {"u64", HAL_U64}};
    for (size_t i = 0; i < sizeof(tab) / sizeof(tab[0]); i++)
        if (name != NULL && strcmp(name, tab[i].n) == 0)
            return tab[i].t;
    return HAL_TYPE_UNSPECIFIED;
}

int hal_q_parse_value(hal_type_t type, const char *text, hal_data_u *out)
{
    char *end;
    hal_data_u v;
    memset(&v, 0, sizeof(v));
    if (text == NULL || text[0] == '\0')
        return -EINVAL;
    errno = 0;
    switch (type) {
    case HAL_BIT:
        if (strcmp(text, "1") == 0 || strcasecmp(text, "TRUE") == 0)
            v.b = 1;
        else if (strcmp(text, "0") == 0 || strcasecmp(text, "FALSE") == 0)
            v.b = 0;
        else
            return -EINVAL;
        break;
    case HAL_FLOAT: {
        double d = strtod(text, &end);
        if (*end != '\0' || end == text)
            return -EINVAL;
        if (errno == ERANGE && isinf(d))
            return -ERANGE;
        v.f = d;
        break;
    }
    case HAL_S32: {
        long long x = strtoll(text, &end, 0);
        if (*end != '\0' || end == text)
            return -EINVAL;
        if (errno == ERANGE || x < INT32_MIN || x > INT32_MAX)
            return -ERANGE;
        v.s = (rtapi_s32)x;
        break;
    }
    case HAL_U32: {
        const char *p = text;
        while (*p == ' ')
            p++;
        if (*p == '-') {
            /* strtoull accepts "-1"; a negative number is out of range. */
            strtoll(text, &end, 0);
            return (*end != '\0' || end == text) ? -EINVAL : -ERANGE;
        }
        unsigned long long x = strtoull(text, &end, 0);
        if (*end != '\0' || end == text)
            return -EINVAL;
        if (errno == ERANGE || x > UINT32_MAX)
            return -ERANGE;
        v.u = (rtapi_u32)x;
        break;
    }
    case HAL_S64: {
        long long x = strtoll(text, &end, 0);
        if (*end != '\0' || end == text)
            return -EINVAL;
        if (errno == ERANGE)
            return -ERANGE;
        v.ls = x;
        break;
    }
    case HAL_U64: {
        const char *p = text;
        while (*p == ' ')
            p++;
        if (*p == '-') {
            strtoll(text, &end, 0);
            return (*end != '\0' || end == text) ? -EINVAL : -ERANGE;
        }
        unsigned long long x = strtoull(text, &end, 0);
        if (*end != '\0' || end == text)
            return -EINVAL;
        if (errno == ERANGE)
            return -ERANGE;
        v.lu = x;
        break;
    }
    default:
        return -EINVAL;
    }
    if (out != NULL)
        *out = v;
    return 0;
}

int hal_q_format_value(hal_type_t type, const hal_data_u *v, char *buf, size_t len)
{
    switch (type) {
    case HAL_BIT: return snprintf(buf, len, "%s", v->b ? "TRUE" : "FALSE");
    case HAL_FLOAT: return snprintf(buf, len, "%.7g", (double)v->f);
    case HAL_S32: return snprintf(buf, len, "%ld", (long)v->s);
    case HAL_U32: return snprintf(buf, len, "%lu", (unsigned long)v->u);
    case HAL_S64: return snprintf(buf, len, "%" PRId64, (int64_t)v->ls);
    case HAL_U64: return snprintf(buf, len, "%" PRIu64, (uint64_t)v->lu);
    default: return snprintf(buf, len, "unknown_type");
    }
}

void read_typed(hal_type_t type, const volatile void *src, hal_data_u *out)
{
    memset(out, 0, sizeof(*out));
    switch (type) {
    case HAL_BIT: out->b = *(const volatile hal_bit_t *)src; break;
    case HAL_FLOAT: out->f = *(const volatile hal_float_t *)src; break;
    case HAL_S32: out->s = *(const volatile hal_s32_t *)src; break;
    case HAL_U32: out->u = *(const volatile hal_u32_t *)src; break;
    case HAL_S64: out->ls = *(const volatile hal_s64_t *)src; break;
    case HAL_U64: out->lu = *(const volatile hal_u64_t *)src; break;
    default: break;
    }
}

void write_typed(hal_type_t type, volatile void *dst, const hal_data_u *in)
{
    switch (type) {
    case HAL_BIT: *(volatile hal_bit_t *)dst = in->b; break;
    case HAL_FLOAT: *(volatile hal_float_t *)dst = in->f; break;
    case HAL_S32: *(volatile hal_s32_t *)dst = in->s; break;
    case HAL_U32: *(volatile hal_u32_t *)dst = in->u; break;
    case HAL_S64: *(volatile hal_s64_t *)dst = in->ls; break;
    case HAL_U64: *(volatile hal_u64_t *)dst = in->lu; break;
    default: break;
    }
}

static const char *type_upper(hal_type_t t)
{
    switch (t) {
    case HAL_BIT: return "bit";
    case HAL_FLOAT: return "float";
    case HAL_S32: return "S32";
    case HAL_U32: return "U32";
    case HAL_S64: return "S64";
    case HAL_U64: return "U64";
    default: return "unknown";
    }
}

static int value_error(int rc, hal_type_t type, const char *value, char *err, size_t errlen)
{
    if (rc == -ERANGE)
        SETERR("value '%s' out of range for %s", value, type_upper(type));
    else
        SETERR("value '%s' invalid for %s", value, type_upper(type));
    return rc;
}

int hal_q_getp(const char *name, char *buf, size_t len, hal_type_t *type, char *err,
               size_t errlen)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_data_u v;
    hal_type_t t;
    hal_priv_lock();
    hal_param_t *pa = halpr_find_param_by_name(name);
    hal_pin_t *pi = pa ? NULL : halpr_find_pin_by_name(name);
    if (pa != NULL) {
        t = pa->type;
        read_typed(t, halpr_param_value(pa), &v);
    } else if (pi != NULL) {
        t = pi->type;
        read_typed(t, halpr_pin_value(pi), &v);
    }
    hal_priv_unlock();
    if (pa == NULL && pi == NULL) {
        SETERR("pin or parameter '%s' not found", name);
        return -ENOENT;
    }
    if (type)
        *type = t;
    if (buf)
        hal_q_format_value(t, &v, buf, len);
    return 0;
}

int hal_q_setp(const char *name, const char *value, char *err, size_t errlen)
{
    if (name == NULL || value == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    int rc = 0;
    hal_data_u v;
    hal_param_t *pa = halpr_find_param_by_name(name);
    if (pa != NULL) {
        /* Like LinuxCNC's halcmd, setp is not subject to the HAL lock. */
        if (pa->dir == HAL_RO) {
            SETERR("param '%s' is not writable", name);
            rc = -EPERM;
        } else if ((rc = hal_q_parse_value(pa->type, value, &v)) != 0) {
            value_error(rc, pa->type, value, err, errlen);
        } else {
            write_typed(pa->type, halpr_param_value(pa), &v);
        }
        hal_priv_unlock();
        return rc;
    }
    hal_pin_t *pi = halpr_find_pin_by_name(name);
    if (pi == NULL) {
        SETERR("parameter or pin '%s' not found", name);
        rc = -ENOENT;
    } else if (pi->dir == HAL_OUT) {
        SETERR("pin '%s' is not writable", name);
        rc = -EPERM;
    } else if (pi->signal != 0) {
        SETERR("pin '%s' is connected to a signal", name);
        rc = -EPERM;
    } else if ((rc = hal_q_parse_value(pi->type, value, &v)) != 0) {
        value_error(rc, pi->type, value, err, errlen);
    } else {
        write_typed(pi->type, &pi->dummysig, &v);
    }
    hal_priv_unlock();
    return rc;
}

int hal_q_gets(const char *name, char *buf, size_t len, hal_type_t *type, char *err,
               size_t errlen)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_sig_t *s = halpr_find_sig_by_name(name);
    hal_data_u v;
    hal_type_t t = HAL_TYPE_UNSPECIFIED;
    if (s != NULL) {
        t = s->type;
        read_typed(t, halpr_sig_value(s), &v);
    }
    hal_priv_unlock();
    if (s == NULL) {
        SETERR("signal '%s' not found", name);
        return -ENOENT;
    }
    if (type)
        *type = t;
    if (buf)
        hal_q_format_value(t, &v, buf, len);
    return 0;
}

int hal_q_sets(const char *name, const char *value, char *err, size_t errlen)
{
    if (name == NULL || value == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    int rc = 0;
    hal_data_u v;
    hal_sig_t *s = halpr_find_sig_by_name(name);
    if (s == NULL) {
        SETERR("signal '%s' not found", name);
        rc = -ENOENT;
    } else if (s->writers > 0) {
        SETERR("signal '%s' already has writer(s)", name);
        rc = -EPERM;
    } else if ((rc = hal_q_parse_value(s->type, value, &v)) != 0) {
        value_error(rc, s->type, value, err, errlen);
    } else {
        write_typed(s->type, halpr_sig_value(s), &v);
    }
    hal_priv_unlock();
    return rc;
}
