/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _POSIX_C_SOURCE 200809L
#include "fake_hal.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_OBJS 8192
#define MAX_ALLOCS 8192

static struct fake_obj objs[MAX_OBJS];
static int nobjs;
static void *allocs[MAX_ALLOCS];
static int nallocs;
static int fail_at = -1;
static int created;

void fake_hal_reset(void)
{
    for (int i = 0; i < nallocs; i++)
        free(allocs[i]);
    nallocs = 0;
    nobjs = 0;
    fail_at = -1;
    created = 0;
}

void fake_hal_fail_at(int index)
{
    fail_at = index < 0 ? -1 : created + index;
}

int fake_hal_objects(void)
{
    return nobjs;
}

void *hal_malloc(long size)
{
    if (nallocs >= MAX_ALLOCS)
        return NULL;
    void *p = calloc(1, (size_t)size);
    allocs[nallocs++] = p;
    return p;
}

static int add(const char *name, enum fake_kind kind, hal_type_t type, int dir,
               volatile void *data, int comp_id)
{
    if (fail_at >= 0 && created == fail_at) {
        created++;
        return -ENOMEM;
    }
    created++;
    if (strlen(name) > HAL_NAME_LEN) {
        fprintf(stderr, "fake_hal: name too long: %s\n", name);
        return -EINVAL;
    }
    for (int i = 0; i < nobjs; i++)
        if (strcmp(objs[i].name, name) == 0)
            return -EEXIST;
    if (nobjs >= MAX_OBJS)
        return -ENOMEM;
    struct fake_obj *o = &objs[nobjs++];
    memset(o, 0, sizeof(*o));
    snprintf(o->name, sizeof(o->name), "%s", name);
    o->kind = kind;
    o->type = type;
    o->dir = dir;
    o->data = data;
    o->comp_id = comp_id;
    return 0;
}

static int pin_newv(hal_type_t type, hal_pin_dir_t dir, void **ptr, int comp_id, const char *fmt,
                    va_list ap)
{
    char name[256];
    vsnprintf(name, sizeof(name), fmt, ap);
    void *storage = hal_malloc(sizeof(hal_data_u));
    int r = add(name, FAKE_PIN, type, dir, storage, comp_id);
    if (r == 0)
        *ptr = storage;
    return r;
}

#define PIN_NEWF(fn, T, type)                                                      \
    int fn(hal_pin_dir_t dir, T **p, int comp_id, const char *fmt, ...)            \
    {                                                                              \
        va_list ap;                                                                \
        va_start(ap, fmt);                                                         \
        int r = pin_newv(type, dir, (void **)p, comp_id, fmt, ap);                 \
        va_end(ap);                                                                \
        return r;                                                                  \
    }
PIN_NEWF(hal_pin_bit_newf, hal_bit_t, HAL_BIT)
PIN_NEWF(hal_pin_float_newf, hal_float_t, HAL_FLOAT)
PIN_NEWF(hal_pin_u32_newf, hal_u32_t, HAL_U32)
PIN_NEWF(hal_pin_s32_newf, hal_s32_t, HAL_S32)

#define PARAM_NEWF(fn, T, type)                                                    \
    int fn(hal_param_dir_t dir, T *data, int comp_id, const char *fmt, ...)        \
    {                                                                              \
        char name[256];                                                            \
        va_list ap;                                                                \
        va_start(ap, fmt);                                                         \
        vsnprintf(name, sizeof(name), fmt, ap);                                    \
        va_end(ap);                                                                \
        return add(name, FAKE_PARAM, type, dir, data, comp_id);                    \
    }
PARAM_NEWF(hal_param_bit_newf, hal_bit_t, HAL_BIT)
PARAM_NEWF(hal_param_float_newf, hal_float_t, HAL_FLOAT)
PARAM_NEWF(hal_param_u32_newf, hal_u32_t, HAL_U32)
PARAM_NEWF(hal_param_s32_newf, hal_s32_t, HAL_S32)

int hal_param_alias(const char *param_name, const char *alias)
{
    const struct fake_obj *t = fake_hal_find(param_name);
    if (!t || t->kind != FAKE_PARAM)
        return -ENOENT;
    int r = add(alias, FAKE_ALIAS, t->type, t->dir, t->data, t->comp_id);
    if (r == 0)
        snprintf(objs[nobjs - 1].target, sizeof(objs[0].target), "%s", param_name);
    return r;
}

int hal_export_functf(void (*funct)(void *, long), void *arg, int uses_fp, int reentrant,
                      int comp_id, const char *fmt, ...)
{
    char name[256];
    va_list ap;
    (void)uses_fp;
    (void)reentrant;
    va_start(ap, fmt);
    vsnprintf(name, sizeof(name), fmt, ap);
    va_end(ap);
    int r = add(name, FAKE_FUNCT, HAL_TYPE_UNSPECIFIED, 0, NULL, comp_id);
    if (r == 0) {
        objs[nobjs - 1].funct = funct;
        objs[nobjs - 1].arg = arg;
    }
    return r;
}

int fake_hal_count(const char *prefix, int kind)
{
    int n = 0;
    for (int i = 0; i < nobjs; i++)
        if (strncmp(objs[i].name, prefix, strlen(prefix)) == 0 &&
            (kind < 0 || (int)objs[i].kind == kind))
            n++;
    return n;
}

const struct fake_obj *fake_hal_find(const char *name)
{
    for (int i = 0; i < nobjs; i++)
        if (strcmp(objs[i].name, name) == 0)
            return &objs[i];
    return NULL;
}

static volatile void *need(const char *name, hal_type_t type)
{
    const struct fake_obj *o = fake_hal_find(name);
    if (!o || o->type != type || !o->data) {
        fprintf(stderr, "fake_hal: no %s object %s\n", hal_type_name(type), name);
        abort();
    }
    return o->data;
}

hal_bit_t *fake_bit(const char *name) { return (hal_bit_t *)need(name, HAL_BIT); }
hal_float_t *fake_float(const char *name) { return (hal_float_t *)need(name, HAL_FLOAT); }
hal_s32_t *fake_s32(const char *name) { return (hal_s32_t *)need(name, HAL_S32); }
hal_u32_t *fake_u32(const char *name) { return (hal_u32_t *)need(name, HAL_U32); }

void fake_run(const char *funct, long period)
{
    const struct fake_obj *o = fake_hal_find(funct);
    if (!o || o->kind != FAKE_FUNCT) {
        fprintf(stderr, "fake_hal: no function %s\n", funct);
        abort();
    }
    o->funct(o->arg, period);
}

const char *hal_type_name(hal_type_t type)
{
    switch (type) {
    case HAL_BIT: return "bit";
    case HAL_FLOAT: return "float";
    case HAL_S32: return "s32";
    case HAL_U32: return "u32";
    default: return "?";
    }
}
