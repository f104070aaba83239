/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halmodule.c - the `_hal` C extension behind the Python `hal` module:
 * userspace HAL components written in Python, and module-level helpers to
 * inspect and change the HAL by name.  hal.py (next to this file) wraps it
 * the way LinuxCNC's hal.py wraps its _hal, so `import hal` code written
 * for LinuxCNC 2.9 runs unchanged.  Behaviour, messages and exception types
 * follow LinuxCNC 2.9's module as observed on it (see docs/hal-python.md
 * and tests/python/), including its habit of returning False on success
 * and True on failure from new_sig/connect/disconnect/set_p.
 *
 * Pins are created with their pointer slot (and parameters with their
 * value) in HAL shared memory, as libhal requires of every component.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <errno.h>
#include <inttypes.h>
#include <limits.h>
#include <string.h>

#include "hal.h"
#include "hal_query.h"

static PyObject *hal_error; /* hal.error */

/* ---- items (pins and parameters) --------------------------------------- */

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

static PyTypeObject ItemType;

static void state_release(comp_state_t *st)
{
    if (st != NULL && --st->refs == 0)
        PyMem_Free(st);
}

static volatile hal_data_u *item_data(ItemObject *it)
{
    if (it->is_pin)
        return (volatile hal_data_u *)*it->pin_slot;
    return it->param;
}

static const char *type_upper(hal_type_t t)
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

static const char *dir_upper(int is_pin, int dir)
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

static PyObject *value_to_py(hal_type_t type, volatile hal_data_u *d)
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
static int py_to_value(hal_type_t type, PyObject *v, volatile hal_data_u *d)
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

static PyObject *item_get(ItemObject *it, PyObject *unused)
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

static PyTypeObject ItemType = {
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

/* ---- components --------------------------------------------------------- */

typedef struct {
    PyObject_HEAD
    int comp_id; /* > 0 while the component exists */
    char name[HAL_NAME_LEN + 1];
    char prefix[HAL_NAME_LEN + 1];
    PyObject *items; /* dict: short name -> ItemObject */
    comp_state_t *state;
} CompObject;

static PyTypeObject CompType;

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

static PyTypeObject CompType = {
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

/* ---- module-level helpers ----------------------------------------------- */

static int attach_or_raise(void)
{
    int r = hal_q_attach();
    if (r < 0) {
        PyErr_Format(PyExc_RuntimeError, "cannot attach to the HAL session: %s", strerror(-r));
        return -1;
    }
    return 0;
}

static PyObject *py_component_exists(PyObject *self, PyObject *args)
{
    const char *name;
    (void)self;
    if (!PyArg_ParseTuple(args, "s", &name) || attach_or_raise() < 0)
        return NULL;
    return PyBool_FromLong(hal_q_component_exists(name) > 0);
}

static PyObject *py_component_is_ready(PyObject *self, PyObject *args)
{
    const char *name;
    (void)self;
    if (!PyArg_ParseTuple(args, "s", &name) || attach_or_raise() < 0)
        return NULL;
    return PyBool_FromLong(hal_q_component_ready(name) > 0);
}

static int valid_type(int t)
{
    return t == HAL_BIT || t == HAL_FLOAT || t == HAL_S32 || t == HAL_U32 || t == HAL_S64 ||
           t == HAL_U64;
}

static PyObject *py_new_sig(PyObject *self, PyObject *args)
{
    const char *name;
    int type;
    (void)self;
    if (!PyArg_ParseTuple(args, "si", &name, &type) || attach_or_raise() < 0)
        return NULL;
    if (!valid_type(type)) {
        PyErr_SetString(PyExc_RuntimeError, "not a valid HAL signal type");
        return NULL;
    }
    return PyBool_FromLong(hal_signal_new(name, (hal_type_t)type) != 0);
}

static PyObject *py_connect(PyObject *self, PyObject *args)
{
    const char *pin, *sig;
    (void)self;
    if (!PyArg_ParseTuple(args, "ss", &pin, &sig) || attach_or_raise() < 0)
        return NULL;
    return PyBool_FromLong(hal_link(pin, sig) != 0);
}

static PyObject *py_disconnect(PyObject *self, PyObject *args)
{
    const char *pin;
    (void)self;
    if (!PyArg_ParseTuple(args, "s", &pin) || attach_or_raise() < 0)
        return NULL;
    return PyBool_FromLong(hal_unlink(pin) != 0);
}

static PyObject *py_pin_has_writer(PyObject *self, PyObject *args)
{
    const char *pin;
    hal_q_pin_t p;
    (void)self;
    if (!PyArg_ParseTuple(args, "s", &pin) || attach_or_raise() < 0)
        return NULL;
    if (hal_q_pin(pin, &p) < 0) {
        PyErr_Format(PyExc_NameError, "Pin `%s' does not exist", pin);
        return NULL;
    }
    return PyBool_FromLong(hal_q_pin_has_writer(pin) > 0);
}

static PyObject *py_get_value(PyObject *self, PyObject *args)
{
    const char *name;
    hal_q_pin_t p;
    hal_q_sig_t s;
    (void)self;
    if (!PyArg_ParseTuple(args, "s", &name) || attach_or_raise() < 0)
        return NULL;
    if (hal_q_pin(name, &p) == 0 || hal_q_param(name, &p) == 0)
        return value_to_py(p.type, &p.value);
    if (hal_q_sig(name, &s) == 0)
        return value_to_py(s.type, &s.value);
    PyErr_Format(PyExc_RuntimeError, "Can't set value: pin / param %s not found", name);
    return NULL;
}

static PyObject *py_set_p(PyObject *self, PyObject *args)
{
    const char *name, *value;
    hal_q_pin_t p;
    char err[256];
    (void)self;
    if (!PyArg_ParseTuple(args, "ss", &name, &value) || attach_or_raise() < 0)
        return NULL;
    if (hal_q_pin(name, &p) == 0) {
        if (p.dir == HAL_OUT) {
            PyErr_SetString(PyExc_RuntimeError, "pin not writable");
            return NULL;
        }
        if (p.signal[0] != '\0') {
            PyErr_SetString(PyExc_RuntimeError, "pin connected to signal");
            return NULL;
        }
    } else if (hal_q_param(name, &p) == 0) {
        if (p.dir == HAL_RO) {
            PyErr_SetString(PyExc_RuntimeError, "param not writable");
            return NULL;
        }
    } else {
        PyErr_SetString(PyExc_RuntimeError, "pin not found");
        return NULL;
    }
    /* 2.9 reports a bad value only through the return value */
    int r = hal_q_setp(name, value, err, sizeof(err));
    return PyBool_FromLong(r != 0);
}

static PyObject *py_set_s(PyObject *self, PyObject *args)
{
    const char *name, *value;
    hal_q_sig_t s;
    char err[256];
    (void)self;
    if (!PyArg_ParseTuple(args, "ss", &name, &value) || attach_or_raise() < 0)
        return NULL;
    if (hal_q_sig(name, &s) < 0) {
        PyErr_SetString(PyExc_RuntimeError, "signal not found");
        return NULL;
    }
    if (s.writers > 0) {
        PyErr_SetString(PyExc_RuntimeError, "signal not writable");
        return NULL;
    }
    int r = hal_q_sets(name, value, err, sizeof(err));
    return PyBool_FromLong(r != 0);
}

typedef struct {
    PyObject *list;
    hal_q_kind_t kind;
    int failed;
} info_ctx_t;

static int add_info(PyObject *d, const char *key, PyObject *v)
{
    if (v == NULL)
        return -1;
    int r = PyDict_SetItemString(d, key, v);
    Py_DECREF(v);
    return r;
}

static int info_cb(const char *name, void *vctx)
{
    info_ctx_t *ctx = vctx;
    PyObject *d = PyDict_New();
    if (d == NULL)
        goto fail;
    if (ctx->kind == HAL_Q_SIG) {
        hal_q_sig_t s;
        char driver[HAL_NAME_LEN + 1] = "";
        if (hal_q_sig(name, &s) < 0) {
            Py_DECREF(d);
            return 0; /* deleted meanwhile */
        }
        if (s.writers > 0 || s.bidirs > 0) {
            char pins[64][HAL_NAME_LEN + 1];
            int n = hal_q_sig_pins(name, pins, 64);
            for (int i = 0; i < n && i < 64; i++) {
                hal_q_pin_t p;
                if (hal_q_pin(pins[i], &p) == 0 && p.dir == HAL_OUT) {
                    memcpy(driver, pins[i], sizeof(driver));
                    driver[HAL_NAME_LEN] = '\0';
                    break;
                }
            }
        }
        if (add_info(d, "NAME", PyUnicode_FromString(name)) < 0 ||
            add_info(d, "VALUE", value_to_py(s.type, &s.value)) < 0 ||
            add_info(d, "DRIVER", driver[0] ? PyUnicode_FromString(driver) : Py_NewRef(Py_None)) <
                0 ||
            add_info(d, "TYPE", PyLong_FromLong(s.type)) < 0)
            goto fail;
    } else {
        hal_q_pin_t p;
        int r = ctx->kind == HAL_Q_PIN ? hal_q_pin(name, &p) : hal_q_param(name, &p);
        if (r < 0) {
            Py_DECREF(d);
            return 0;
        }
        /* key order as 2.9: pins NAME VALUE DIRECTION TYPE, params NAME
         * DIRECTION VALUE */
        if (add_info(d, "NAME", PyUnicode_FromString(name)) < 0)
            goto fail;
        if (ctx->kind == HAL_Q_PIN) {
            if (add_info(d, "VALUE", value_to_py(p.type, &p.value)) < 0 ||
                add_info(d, "DIRECTION", PyLong_FromLong(p.dir)) < 0 ||
                add_info(d, "TYPE", PyLong_FromLong(p.type)) < 0)
                goto fail;
        } else if (add_info(d, "DIRECTION", PyLong_FromLong(p.dir)) < 0 ||
                   add_info(d, "VALUE", value_to_py(p.type, &p.value)) < 0) {
            goto fail;
        }
    }
    if (PyList_Append(ctx->list, d) < 0)
        goto fail;
    Py_DECREF(d);
    return 0;
fail:
    Py_XDECREF(d);
    ctx->failed = 1;
    return 1;
}

static PyObject *get_info(hal_q_kind_t kind)
{
    if (attach_or_raise() < 0)
        return NULL;
    info_ctx_t ctx = {PyList_New(0), kind, 0};
    if (ctx.list == NULL)
        return NULL;
    hal_q_foreach(kind, NULL, info_cb, &ctx);
    if (ctx.failed) {
        Py_DECREF(ctx.list);
        return NULL;
    }
    return ctx.list;
}

static PyObject *py_get_info_pins(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    return get_info(HAL_Q_PIN);
}

static PyObject *py_get_info_params(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    return get_info(HAL_Q_PARAM);
}

static PyObject *py_get_info_signals(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    return get_info(HAL_Q_SIG);
}

static PyObject *py_get_msg_level(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    return PyLong_FromLong(rtapi_get_msg_level());
}

static PyObject *py_set_msg_level(PyObject *self, PyObject *args)
{
    int level;
    (void)self;
    if (!PyArg_ParseTuple(args, "i", &level))
        return NULL;
    if (level < RTAPI_MSG_NONE || level > RTAPI_MSG_ALL) {
        PyErr_Format(PyExc_RuntimeError, "invalid message level %d (%d to %d)", level,
                     RTAPI_MSG_NONE, RTAPI_MSG_ALL);
        return NULL;
    }
    rtapi_set_msg_level(level);
    Py_RETURN_NONE;
}

static PyMethodDef module_methods[] = {
    {"component_exists", py_component_exists, METH_VARARGS,
     ".component_exists('component_name'): Return a TRUE value if the named component exists"},
    {"component_is_ready", py_component_is_ready, METH_VARARGS,
     ".component_is_ready('component_name'): Return a TRUE value if the named component is "
     "ready"},
    {"new_sig", py_new_sig, METH_VARARGS,
     ".new_sig('signal_name', type): Create a new signal with the specified name.  'type' is "
     "one of HAL_BIT, HAL_FLOAT, HAL_S32, HAL_U32, HAL_S64 or HAL_U64."},
    {"connect", py_connect, METH_VARARGS,
     ".connect('pin_name', 'signal_name'): Connect the named pin to the named signal."},
    {"disconnect", py_disconnect, METH_VARARGS,
     ".disconnect('pin_name'): Disconnect the named pin from any signal."},
    {"pin_has_writer", py_pin_has_writer, METH_VARARGS,
     ".pin_has_writer('pin_name'): Return a FALSE value if a pin has no writers and TRUE if it "
     "does"},
    {"get_value", py_get_value, METH_VARARGS,
     ".get_value('name'): Gets the pin, param or signal value"},
    {"set_p", py_set_p, METH_VARARGS, ".set_p('name', 'value'): Set the pin or param value"},
    {"set_s", py_set_s, METH_VARARGS,
     ".set_s('signal_name', 'value'): Set the value of a signal that has no writer"},
    {"get_info_pins", py_get_info_pins, METH_NOARGS,
     ".get_info_pins(): Get a list of dicts for all the pins; {NAME:, VALUE:, DIRECTION:, "
     "TYPE:}"},
    {"get_info_params", py_get_info_params, METH_NOARGS,
     ".get_info_params(): Get a list of dicts for all the parameters; {NAME:, VALUE:, "
     "DIRECTION:}"},
    {"get_info_signals", py_get_info_signals, METH_NOARGS,
     ".get_info_signals(): Get a list of dicts for all the signals; {NAME:, VALUE:, DRIVER:, "
     "TYPE:}"},
    {"get_msg_level", py_get_msg_level, METH_NOARGS,
     ".get_msg_level(): Get the RTAPI message level"},
    {"set_msg_level", py_set_msg_level, METH_VARARGS,
     ".set_msg_level(level): Set the RTAPI message level"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef halmodule = {
    PyModuleDef_HEAD_INIT,
    .m_name = "_hal",
    .m_doc = "Interface to the HAL: userspace components in Python and HAL inspection",
    .m_size = -1,
    .m_methods = module_methods,
};

PyMODINIT_FUNC PyInit__hal(void)
{
    if (PyType_Ready(&ItemType) < 0 || PyType_Ready(&CompType) < 0)
        return NULL;
    PyObject *m = PyModule_Create(&halmodule);
    if (m == NULL)
        return NULL;
    hal_error = PyErr_NewException("hal.error", NULL, NULL);
    if (hal_error == NULL || PyModule_AddObjectRef(m, "error", hal_error) < 0 ||
        PyModule_AddObjectRef(m, "component", (PyObject *)&CompType) < 0 ||
        PyModule_AddObjectRef(m, "item", (PyObject *)&ItemType) < 0)
        goto fail;
    struct {
        const char *name;
        long value;
    } consts[] = {
        {"HAL_BIT", HAL_BIT},   {"HAL_FLOAT", HAL_FLOAT},   {"HAL_S32", HAL_S32},
        {"HAL_U32", HAL_U32},   {"HAL_S64", HAL_S64},       {"HAL_U64", HAL_U64},
        {"HAL_IN", HAL_IN},     {"HAL_OUT", HAL_OUT},       {"HAL_IO", HAL_IO},
        {"HAL_RO", HAL_RO},     {"HAL_RW", HAL_RW},         {"MSG_NONE", RTAPI_MSG_NONE},
        {"MSG_ERR", RTAPI_MSG_ERR}, {"MSG_WARN", RTAPI_MSG_WARN}, {"MSG_INFO", RTAPI_MSG_INFO},
        {"MSG_DBG", RTAPI_MSG_DBG}, {"MSG_ALL", RTAPI_MSG_ALL},  {"is_kernelspace", 0},
        {"is_userspace", 1},    {"is_rt", 0},               {"is_sim", 1},
    };
    for (size_t i = 0; i < sizeof(consts) / sizeof(consts[0]); i++)
        if (PyModule_AddIntConstant(m, consts[i].name, consts[i].value) < 0)
            goto fail;
    if (PyModule_AddStringConstant(m, "kernel_version", "Not Available") < 0)
        goto fail;
    return m;
fail:
    Py_XDECREF(hal_error);
    Py_DECREF(m);
    return NULL;
}
