/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halpy_comp.c - hal.component: a userspace HAL component written in
 * Python (pins and parameters by name, ready, exit, prefix).
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <string.h>

#include "halpy.h"

/* ---- components --------------------------------------------------------- */



static int comp_check(CompObject *c)
{
    if (c->comp_id <= 0) {
        PyErr_SetString(PyExc_RuntimeError, "Invalid operation on closed HAL component");
        return -1;
    }
    return 0;
}

static void comp_do_exit(CompObject *c)
{
    if (c->comp_id > 0) {
        if (c->state != NULL)
            c->state->alive = 0;
        hal_exit(c->comp_id);
        c->comp_id = 0;
    }
}

static PyObject *comp_new(PyTypeObject *type, PyObject *args, PyObject *kw)
{
    (void)args;
    (void)kw;
    CompObject *c = (CompObject *)type->tp_alloc(type, 0);
    if (c == NULL)
        return NULL;
    c->items = PyDict_New();
    if (c->items == NULL) {
        Py_DECREF(c);
        return NULL;
    }
    return (PyObject *)c;
}

static int comp_init(CompObject *c, PyObject *args, PyObject *kw)
{
    const char *name, *prefix = NULL;
    static char *kwlist[] = {"name", "prefix", NULL};
    if (!PyArg_ParseTupleAndKeywords(args, kw, "s|s:hal.component", kwlist, &name, &prefix))
        return -1;
    if (c->comp_id > 0) {
        PyErr_SetString(hal_error, "component already initialised");
        return -1;
    }
    if (prefix == NULL)
        prefix = name;
    if (strlen(name) > HAL_NAME_LEN) {
        PyErr_Format(hal_error, "Invalid component name length \"%s\": max = %d characters", name,
                     HAL_NAME_LEN);
        return -1;
    }
    if (strlen(prefix) > HAL_NAME_LEN) {
        PyErr_Format(hal_error, "Invalid prefix length \"%s\": max = %d characters", prefix,
                     HAL_NAME_LEN);
        return -1;
    }
    int id = hal_init(name);
    if (id <= 0) {
        PyErr_SetString(hal_error, strerror(id < 0 ? -id : EINVAL));
        return -1;
    }
    c->comp_id = id;
    snprintf(c->name, sizeof(c->name), "%s", name);
    snprintf(c->prefix, sizeof(c->prefix), "%s", prefix);
    c->state = PyMem_Malloc(sizeof(*c->state));
    if (c->state == NULL) {
        comp_do_exit(c);
        PyErr_NoMemory();
        return -1;
    }
    c->state->alive = 1;
    c->state->refs = 1;
    return 0;
}

static void comp_dealloc(CompObject *c)
{
    comp_do_exit(c);
    Py_XDECREF(c->items);
    state_release(c->state);
    Py_TYPE(c)->tp_free((PyObject *)c);
}

static PyObject *comp_new_item(CompObject *c, PyObject *args, int is_pin)
{
    const char *name;
    int type, dir;
    if (!PyArg_ParseTuple(args, is_pin ? "sii:newpin" : "sii:newparam", &name, &type, &dir))
        return NULL;
    if (comp_check(c) < 0)
        return NULL;
    if (type != HAL_BIT && type != HAL_FLOAT && type != HAL_S32 && type != HAL_U32 &&
        type != HAL_S64 && type != HAL_U64) {
        PyErr_Format(hal_error, "Invalid %s type %d", is_pin ? "pin" : "param", type);
        return NULL;
    }
    PyObject *key = PyUnicode_FromString(name);
    if (key == NULL)
        return NULL;
    int dup = PyDict_Contains(c->items, key);
    if (dup != 0) {
        if (dup > 0)
            PyErr_Format(PyExc_ValueError, "Duplicate %s name '%s'", is_pin ? "pin" : "param",
                         name);
        Py_DECREF(key);
        return NULL;
    }
    char full[256];
    snprintf(full, sizeof(full), "%s.%s", c->prefix, name);
    if (strlen(full) > HAL_NAME_LEN) {
        PyErr_Format(hal_error, "Invalid %s name length \"%s\": max = %d characters",
                     is_pin ? "pin" : "param", full, HAL_NAME_LEN);
        Py_DECREF(key);
        return NULL;
    }
    ItemObject *it = PyObject_New(ItemObject, &ItemType);
    if (it == NULL) {
        Py_DECREF(key);
        return NULL;
    }
    snprintf(it->name, sizeof(it->name), "%s", name);
    it->is_pin = is_pin;
    it->type = (hal_type_t)type;
    it->dir = dir;
    it->pin_slot = NULL;
    it->param = NULL;
    it->state = NULL;
    int r;
    if (is_pin) {
        it->pin_slot = hal_malloc(sizeof(void *));
        r = it->pin_slot ? hal_pin_new(full, it->type, (hal_pin_dir_t)dir, it->pin_slot,
                                       c->comp_id)
                         : -ENOMEM;
    } else {
        it->param = hal_malloc(sizeof(hal_data_u));
        if (it->param != NULL)
            memset(it->param, 0, sizeof(*it->param));
        r = it->param ? hal_param_new(full, it->type, (hal_param_dir_t)dir, it->param,
                                      c->comp_id)
                      : -ENOMEM;
    }
    if (r < 0) {
        PyErr_SetString(hal_error, strerror(-r));
        Py_DECREF(it);
        Py_DECREF(key);
        return NULL;
    }
    it->state = c->state;
    c->state->refs++;
    if (PyDict_SetItem(c->items, key, (PyObject *)it) < 0) {
        Py_DECREF(it);
        Py_DECREF(key);
        return NULL;
    }
    Py_DECREF(key);
    return (PyObject *)it;
}

static PyObject *comp_newpin(CompObject *c, PyObject *args)
{
    return comp_new_item(c, args, 1);
}

static PyObject *comp_newparam(CompObject *c, PyObject *args)
{
    return comp_new_item(c, args, 0);
}

static ItemObject *comp_find(CompObject *c, PyObject *key)
{
    if (comp_check(c) < 0)
        return NULL;
    PyObject *it = PyDict_GetItemWithError(c->items, key);
    if (it == NULL) {
        if (!PyErr_Occurred())
            PyErr_Format(PyExc_AttributeError, "Pin '%S' does not exist", key);
        return NULL;
    }
    return (ItemObject *)it;
}

static PyObject *comp_getitem_obj(CompObject *c, PyObject *args)
{
    PyObject *key;
    if (!PyArg_ParseTuple(args, "U:getitem", &key))
        return NULL;
    ItemObject *it = comp_find(c, key);
    if (it == NULL)
        return NULL;
    Py_INCREF(it);
    return (PyObject *)it;
}

static PyObject *comp_subscript(CompObject *c, PyObject *key)
{
    ItemObject *it = comp_find(c, key);
    if (it == NULL)
        return NULL;
    return item_get(it, NULL);
}

static int comp_ass_subscript(CompObject *c, PyObject *key, PyObject *v)
{
    if (v == NULL) {
        PyErr_SetString(PyExc_TypeError, "HAL pins and parameters cannot be deleted");
        return -1;
    }
    ItemObject *it = comp_find(c, key);
    if (it == NULL)
        return -1;
    return py_to_value(it->type, v, item_data(it));
}

static Py_ssize_t comp_len(CompObject *c)
{
    return PyDict_Size(c->items);
}

static PyObject *comp_getattro(CompObject *c, PyObject *attr)
{
    PyObject *r = PyObject_GenericGetAttr((PyObject *)c, attr);
    if (r != NULL || !PyErr_ExceptionMatches(PyExc_AttributeError))
        return r;
    PyErr_Clear();
    return comp_subscript(c, attr);
}

static int comp_setattro(CompObject *c, PyObject *attr, PyObject *v)
{
    /* attributes of the (Python subclass) object itself stay settable */
    if (c->items != NULL && PyDict_Contains(c->items, attr) == 1)
        return comp_ass_subscript(c, attr, v);
    PyObject *descr = _PyType_Lookup(Py_TYPE(c), attr);
    if (descr != NULL || v == NULL)
        return PyObject_GenericSetAttr((PyObject *)c, attr, v);
    return comp_ass_subscript(c, attr, v);
}

static PyObject *comp_getpins(CompObject *c, PyObject *unused)
{
    (void)unused;
    if (comp_check(c) < 0)
        return NULL;
    PyObject *d = PyDict_New();
    if (d == NULL)
        return NULL;
    /* sorted by name, as 2.9 returns them */
    PyObject *keys = PyDict_Keys(c->items);
    if (keys == NULL || PyList_Sort(keys) < 0) {
        Py_XDECREF(keys);
        Py_DECREF(d);
        return NULL;
    }
    for (Py_ssize_t i = 0; i < PyList_GET_SIZE(keys); i++) {
        PyObject *k = PyList_GET_ITEM(keys, i);
        PyObject *v = PyDict_GetItem(c->items, k);
        PyObject *val = v ? item_get((ItemObject *)v, NULL) : NULL;
        if (val == NULL || PyDict_SetItem(d, k, val) < 0) {
            Py_XDECREF(val);
            Py_DECREF(keys);
            Py_DECREF(d);
            return NULL;
        }
        Py_DECREF(val);
    }
    Py_DECREF(keys);
    return d;
}

static PyObject *comp_ready(CompObject *c, PyObject *unused)
{
    (void)unused;
    if (comp_check(c) < 0)
        return NULL;
    int r = hal_ready(c->comp_id);
    if (r < 0) {
        PyErr_SetString(hal_error, strerror(-r));
        return NULL;
    }
    Py_RETURN_NONE;
}

static PyObject *comp_unready(CompObject *c, PyObject *unused)
{
    (void)unused;
    if (comp_check(c) < 0)
        return NULL;
    int r = hal_unready(c->comp_id);
    if (r < 0) {
        PyErr_SetString(hal_error, strerror(-r));
        return NULL;
    }
    Py_RETURN_NONE;
}

static PyObject *comp_exit(CompObject *c, PyObject *unused)
{
    (void)unused;
    comp_do_exit(c);
    Py_RETURN_NONE;
}

static PyObject *comp_getprefix(CompObject *c, PyObject *unused)
{
    (void)unused;
    if (comp_check(c) < 0)
        return NULL;
    return PyUnicode_FromString(c->prefix);
}

static PyObject *comp_setprefix(CompObject *c, PyObject *args)
{
    const char *p;
    if (!PyArg_ParseTuple(args, "s:setprefix", &p))
        return NULL;
    if (comp_check(c) < 0)
        return NULL;
    if (strlen(p) > HAL_NAME_LEN) {
        PyErr_Format(hal_error, "Invalid prefix length \"%s\": max = %d characters", p,
                     HAL_NAME_LEN);
        return NULL;
    }
    snprintf(c->prefix, sizeof(c->prefix), "%s", p);
    Py_RETURN_NONE;
}

static PyObject *comp_repr(CompObject *c)
{
    return PyUnicode_FromFormat("<hal component %s(%d) with %zd pins and params>", c->name,
                                c->comp_id, PyDict_Size(c->items));
}

static PyMethodDef comp_methods[] = {
    {"newpin", (PyCFunction)comp_newpin, METH_VARARGS, "Create a new pin"},
    {"newparam", (PyCFunction)comp_newparam, METH_VARARGS, "Create a new parameter"},
    {"getitem", (PyCFunction)comp_getitem_obj, METH_VARARGS, "Get existing pin object"},
    {"getpins", (PyCFunction)comp_getpins, METH_NOARGS, "Get all pins and values of component"},
    {"ready", (PyCFunction)comp_ready, METH_NOARGS, "Call hal_ready"},
    {"unready", (PyCFunction)comp_unready, METH_NOARGS, "Call hal_unready"},
    {"exit", (PyCFunction)comp_exit, METH_NOARGS, "Call hal_exit"},
    {"getprefix", (PyCFunction)comp_getprefix, METH_NOARGS,
     "Get the prefix for newly created pins and parameters"},
    {"setprefix", (PyCFunction)comp_setprefix, METH_VARARGS,
     "Set the prefix for newly created pins and parameters"},
    {NULL, NULL, 0, NULL},
};

static PyMappingMethods comp_mapping = {
    .mp_length = (lenfunc)comp_len,
    .mp_subscript = (binaryfunc)comp_subscript,
    .mp_ass_subscript = (objobjargproc)comp_ass_subscript,
};

PyTypeObject CompType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "hal.component",
    .tp_basicsize = sizeof(CompObject),
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_doc = "HAL Component",
    .tp_methods = comp_methods,
    .tp_as_mapping = &comp_mapping,
    .tp_getattro = (getattrofunc)comp_getattro,
    .tp_setattro = (setattrofunc)comp_setattro,
    .tp_repr = (reprfunc)comp_repr,
    .tp_init = (initproc)comp_init,
    .tp_new = comp_new,
    .tp_dealloc = (destructor)comp_dealloc,
};
