/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halpy_item.c - hal.item: a pin or parameter of a Python component, with
 * LinuxCNC 2.9's value conversions and messages.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <string.h>

#include "halpy.h"

/* ---- items (pins and parameters) --------------------------------------- */



void state_release(comp_state_t *st)
{
    if (st != NULL && --st->refs == 0)
        PyMem_Free(st);
}

volatile hal_data_u *item_data(ItemObject *it)
{
    if (it->is_pin)
        return (volatile hal_data_u *)*it->pin_slot;
    return it->param;
}

const char *type_upper(hal_type_t t)
{
    switch (t) {
    case HAL_BIT:
        return "BIT";
    case HAL_FLOAT:
        return "FLOAT";
    case HAL_S32:
        return "S32";
    case HAL_U32:
        return "U32";
    case HAL_S64:
        return "S64";
    case HAL_U64:
        return "U64";
    default:
        return "UNKNOWN";
    }
}

const char *dir_upper(int is_pin, int dir)
{
    if (is_pin) {
        switch (dir) {
        case HAL_IN:
            return "IN";
        case HAL_OUT:
            return "OUT";
        case HAL_IO:
            return "IO";
        }
    } else {
        switch (dir) {
        case HAL_RO:
            return "RO";
        case HAL_RW:
            return "RW";
        }
    }
    return "UNKNOWN";
}

PyObject *value_to_py(hal_type_t type, volatile hal_data_u *d)
{
    switch (type) {
    case HAL_BIT:
        return PyBool_FromLong(d->b ? 1 : 0);
    case HAL_FLOAT:
        return PyFloat_FromDouble(d->f);
    case HAL_S32:
        return PyLong_FromLong((long)d->s);
    case HAL_U32:
        return PyLong_FromUnsignedLong((unsigned long)d->u);
    case HAL_S64:
        return PyLong_FromLongLong((long long)d->ls);
    case HAL_U64:
        return PyLong_FromUnsignedLongLong((unsigned long long)d->lu);
    default:
        PyErr_Format(hal_error, "Invalid item type %d", (int)type);
        return NULL;
    }
}

/* Python value -> HAL storage, with 2.9's conversions: bits take any
 * object's truth value, floats a number or a numeric string, integers
 * int(value) (so 1.9 -> 1, "12" -> 12), range-checked. */
int py_to_value(hal_type_t type, PyObject *v, volatile hal_data_u *d)
{
    if (type == HAL_BIT) {
        int t = PyObject_IsTrue(v);
        if (t < 0)
            return -1;
        d->b = t != 0;
        return 0;
    }
    if (type == HAL_FLOAT) {
        PyObject *f;
        if (PyUnicode_Check(v))
            f = PyFloat_FromString(v);
        else if (PyNumber_Check(v))
            f = PyNumber_Float(v);
        else {
            PyErr_Format(PyExc_TypeError, "Number expected, not %s", Py_TYPE(v)->tp_name);
            return -1;
        }
        if (f == NULL)
            return -1;
        d->f = PyFloat_AsDouble(f);
        Py_DECREF(f);
        return 0;
    }
    PyObject *l = PyNumber_Long(v);
    if (l == NULL)
        return -1;
    int overflow = 0;
    long long sv = PyLong_AsLongLongAndOverflow(l, &overflow);
    if (sv == -1 && PyErr_Occurred()) {
        Py_DECREF(l);
        return -1;
    }
    int ok;
    switch (type) {
    case HAL_S32:
        ok = !overflow && sv >= INT32_MIN && sv <= INT32_MAX;
        if (ok)
            d->s = (rtapi_s32)sv;
        break;
    case HAL_U32:
        ok = !overflow && sv >= 0 && sv <= UINT32_MAX;
        if (ok)
            d->u = (rtapi_u32)sv;
        break;
    case HAL_S64:
        ok = !overflow;
        if (ok)
            d->ls = sv;
        break;
    case HAL_U64: {
        ok = overflow >= 0 && (overflow > 0 || sv >= 0);
        if (ok) {
            unsigned long long uv = PyLong_AsUnsignedLongLong(l);
            if (uv == (unsigned long long)-1 && PyErr_Occurred()) {
                PyErr_Clear();
                ok = 0;
            } else {
                d->lu = uv;
            }
        }
        break;
    }
    default:
        Py_DECREF(l);
        PyErr_Format(hal_error, "Invalid item type %d", (int)type);
        return -1;
    }
    if (!ok)
        PyErr_Format(PyExc_OverflowError, "Value %S out of range", l);
    Py_DECREF(l);
    return ok ? 0 : -1;
}

static int item_check(ItemObject *it)
{
    if (it->state == NULL || !it->state->alive) {
        PyErr_SetString(PyExc_RuntimeError, "Invalid operation on closed HAL component");
        return -1;
    }
    return 0;
}

PyObject *item_get(ItemObject *it, PyObject *unused)
{
    (void)unused;
    if (item_check(it) < 0)
        return NULL;
    return value_to_py(it->type, item_data(it));
}

static PyObject *item_set(ItemObject *it, PyObject *arg)
{
    if (item_check(it) < 0)
        return NULL;
    if (py_to_value(it->type, arg, item_data(it)) < 0)
        return NULL;
    Py_RETURN_NONE;
}

static PyObject *item_get_type(ItemObject *it, PyObject *unused)
{
    (void)unused;
    return PyLong_FromLong(it->type);
}

static PyObject *item_get_dir(ItemObject *it, PyObject *unused)
{
    (void)unused;
    return PyLong_FromLong(it->dir);
}

static PyObject *item_get_name(ItemObject *it, PyObject *unused)
{
    (void)unused;
    return PyUnicode_FromString(it->name);
}

static PyObject *item_is_pin(ItemObject *it, PyObject *unused)
{
    (void)unused;
    return PyBool_FromLong(it->is_pin);
}

static PyObject *item_repr(ItemObject *it)
{
    return PyUnicode_FromFormat("<hal %s \"%s\" %s-%s>", it->is_pin ? "pin" : "param", it->name,
                                type_upper(it->type), dir_upper(it->is_pin, it->dir));
}

static int item_init(PyObject *self, PyObject *args, PyObject *kw)
{
    (void)self;
    (void)args;
    (void)kw;
    PyErr_SetString(PyExc_RuntimeError, "Cannot be constructed directly");
    return -1;
}

static void item_dealloc(ItemObject *it)
{
    state_release(it->state);
    Py_TYPE(it)->tp_free((PyObject *)it);
}

static PyMethodDef item_methods[] = {
    {"get", (PyCFunction)item_get, METH_NOARGS, "Get item value"},
    {"set", (PyCFunction)item_set, METH_O, "Set item value"},
    {"get_type", (PyCFunction)item_get_type, METH_NOARGS, "Get item type"},
    {"get_dir", (PyCFunction)item_get_dir, METH_NOARGS, "Get item direction"},
    {"get_name", (PyCFunction)item_get_name, METH_NOARGS, "Get item name"},
    {"is_pin", (PyCFunction)item_is_pin, METH_NOARGS, "If item is pin or param"},
    {NULL, NULL, 0, NULL},
};

PyTypeObject ItemType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "hal.item",
    .tp_basicsize = sizeof(ItemObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "HAL Pin",
    .tp_methods = item_methods,
    .tp_repr = (reprfunc)item_repr,
    .tp_init = item_init,
    .tp_dealloc = (destructor)item_dealloc,
    .tp_new = PyType_GenericNew,
};
