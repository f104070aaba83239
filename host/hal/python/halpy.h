/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halpy.h - the parts of the `_hal` extension (halmodule.c: module
 * functions and init; halpy_item.c: pins and parameters; halpy_comp.c:
 * components) and what they share.
 */
#ifndef HM_HALPY_H
#define HM_HALPY_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "hal.h"
#include "hal_query.h"

#pragma GCC visibility push(hidden)

typedef struct {
    int alive; /* cleared by component exit: items must not touch HAL then */
    int refs;
} comp_state_t;

typedef struct {
    PyObject_HEAD
    char name[HAL_NAME_LEN + 1]; /* without the component prefix */
    int is_pin;
    hal_type_t type;
    int dir;
    void **pin_slot;     /* pins: the pointer libhal repoints on link */
    hal_data_u *param;   /* parameters: the value */
    comp_state_t *state; /* shared with the component */
} ItemObject;

typedef struct {
    PyObject_HEAD
    int comp_id; /* > 0 while the component exists */
    char name[HAL_NAME_LEN + 1];
    char prefix[HAL_NAME_LEN + 1];
    PyObject *items; /* dict: short name -> ItemObject */
    comp_state_t *state;
} CompObject;

extern PyTypeObject ItemType, CompType;
extern PyObject *hal_error; /* hal.error */

void state_release(comp_state_t *st);
const char *type_upper(hal_type_t t);
const char *dir_upper(int is_pin, int dir);
PyObject *value_to_py(hal_type_t type, volatile hal_data_u *d);
int py_to_value(hal_type_t type, PyObject *v, volatile hal_data_u *d);
int attach_or_raise(void);
int valid_type(int t);
/* An item's current value as a Python object; its storage. */
PyObject *item_get(ItemObject *it, PyObject *unused);
volatile hal_data_u *item_data(ItemObject *it);

#pragma GCC visibility pop

#endif /* HM_HALPY_H */
