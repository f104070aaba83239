/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * fake_hal.h - an in-process test double of the HAL API (hal.h) for the
 * driver unit tests: records every pin, parameter, alias and function so a
 * test can look them up by name, drive input pins, run functions, count
 * what a board exported, and make the N-th export fail.
 */
#ifndef HM2_FAKE_HAL_H
#define HM2_FAKE_HAL_H

#include "hal.h"

enum fake_kind { FAKE_PIN, FAKE_PARAM, FAKE_FUNCT, FAKE_ALIAS };

struct fake_obj {
    char name[128];
    enum fake_kind kind;
    hal_type_t type;
    int dir;
    volatile void *data; /* pin: storage; param: the component's variable */
    void (*funct)(void *, long);
    void *arg;
    int comp_id;
    char target[128]; /* alias: what it names */
};

void fake_hal_reset(void);
/* The index-th object creation from now on fails with -ENOMEM (-1: never). */
void fake_hal_fail_at(int index);
int fake_hal_count(const char *prefix, int kind); /* kind -1: any */
const struct fake_obj *fake_hal_find(const char *name);
/* typed accessors; abort the test binary if the object is missing */
hal_bit_t *fake_bit(const char *name);
hal_float_t *fake_float(const char *name);
hal_s32_t *fake_s32(const char *name);
hal_u32_t *fake_u32(const char *name);
void fake_run(const char *funct, long period);
int fake_hal_objects(void);

#endif
