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

#include "halpy.h"

PyObject *hal_error; /* hal.error */

/* ---- module-level helpers ----------------------------------------------- */

int attach_or_raise(void)
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

int valid_type(int t)
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
