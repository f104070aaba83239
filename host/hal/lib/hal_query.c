/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_query.c - introspection and modification by name (hal_query.h).
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

#include "hal_priv.h"
#include "hal_query.h"

#define SETERR(...)                                   \
    do {                                              \
        if (err != NULL && errlen > 0)                \
            snprintf(err, errlen, __VA_ARGS__);       \
    } while (0)

int hal_q_attach(void) { return hal_priv_attach(); }

int hal_q_match(const char *pattern, const char *name)
{
    if (pattern == NULL || pattern[0] == '\0')
        return 1;
    if (strncmp(pattern, name, strlen(pattern)) == 0)
        return 1;
    return fnmatch(pattern, name, 0) == 0;
}

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

static void read_typed(hal_type_t type, const volatile void *src, hal_data_u *out)
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

static void write_typed(hal_type_t type, volatile void *dst, const hal_data_u *in)
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

int hal_q_funct(const char *name, hal_q_funct_t *out)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_funct_t *f = halpr_find_funct_by_name(name);
    if (f != NULL && out != NULL) {
        memset(out, 0, sizeof(*out));
        snprintf(out->name, sizeof(out->name), "%s", f->name);
        out->owner_id = ((hal_comp_t *)SHMPTR(f->owner))->id;
        out->uses_fp = f->uses_fp;
        out->reentrant = f->reentrant;
        out->users = f->users;
        out->code_addr = f->funct;
        out->arg = f->arg;
    }
    hal_priv_unlock();
    return f ? 0 : -ENOENT;
}

int hal_q_thread(const char *name, hal_q_thread_t *out)
{
    if (name == NULL || hal_priv_attach() != 0)
        return -EINVAL;
    hal_priv_lock();
    hal_thread_t *t = halpr_find_thread_by_name(name);
    if (t != NULL && out != NULL) {
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
