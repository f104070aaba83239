# SPDX-License-Identifier: GPL-2.0-or-later
"""API probe of the Python `hal` module: every call's result or exception.

Run inside a HAL session (`loadusr -w python3 probe_api.py`).  The same
script was run under LinuxCNC 2.9; its output is probe_api.linuxcnc.out
(captured there, see tests/python/README).  test_hal_python.py compares
our output with it after removing object addresses and libhal's own
"HAL: ERROR" lines.  Calls whose 2.9 behaviour we deliberately do not copy
(module helpers before/after a component exists, set_s) are tested
separately.
"""

import hal


def t(label, f):
    try:
        r = f()
        print(label, "->", repr(r))
    except BaseException as e:
        print(label, "EXC", type(e).__module__, type(e).__name__, repr(str(e)))


c = hal.component("pyc")
t("newpin f in", lambda: c.newpin("fin", hal.HAL_FLOAT, hal.HAL_IN))
t("newpin b out", lambda: c.newpin("bout", hal.HAL_BIT, hal.HAL_OUT))
t("newpin s io", lambda: c.newpin("sio", hal.HAL_S32, hal.HAL_IO))
t("newpin u out", lambda: c.newpin("uout", hal.HAL_U32, hal.HAL_OUT))
t("newparam f rw", lambda: c.newparam("prw", hal.HAL_FLOAT, hal.HAL_RW))
t("newparam s ro", lambda: c.newparam("pro", hal.HAL_S32, hal.HAL_RO))
t("dup pin", lambda: c.newpin("fin", hal.HAL_FLOAT, hal.HAL_IN))
t("bad type", lambda: c.newpin("x1", 99, hal.HAL_IN))
t("bad dir", lambda: c.newpin("x2", hal.HAL_FLOAT, 99))
t("param dir as pin", lambda: c.newpin("x3", hal.HAL_FLOAT, hal.HAL_RW))
t("pin dir as param", lambda: c.newparam("x4", hal.HAL_FLOAT, hal.HAL_IN))
t("type str", lambda: c.newpin("x5", "float", hal.HAL_IN))
t("long name", lambda: c.newpin("x" * 60, hal.HAL_FLOAT, hal.HAL_IN))
t("getitem fin", lambda: c["fin"])
t("getattr fin", lambda: c.fin)
t("getitem missing", lambda: c["nope"])
t("getattr missing", lambda: c.nope)
t("set bout True", lambda: c.__setitem__("bout", True))
t("get bout", lambda: c["bout"])
t("set bout 2", lambda: c.__setitem__("bout", 2))
t("get bout", lambda: c["bout"])
t("set bout 'x'", lambda: c.__setitem__("bout", "x"))
t("set fin 1.5 (IN pin)", lambda: c.__setitem__("fin", 1.5))
t("get fin", lambda: c["fin"])
t("set sio 7", lambda: c.__setitem__("sio", 7))
t("set sio 1.9", lambda: c.__setitem__("sio", 1.9))
t("get sio", lambda: c["sio"])
t("set sio 2**31", lambda: c.__setitem__("sio", 2**31))
t("get sio", lambda: c["sio"])
t("set sio 'abc'", lambda: c.__setitem__("sio", "abc"))
t("set uout -1", lambda: c.__setitem__("uout", -1))
t("get uout", lambda: c["uout"])
t("set uout 2**32", lambda: c.__setitem__("uout", 2**32))
t("get uout", lambda: c["uout"])
t("set uout 3.7", lambda: c.__setitem__("uout", 3.7))
t("get uout", lambda: c["uout"])
t("set prw 2", lambda: c.__setitem__("prw", 2))
t("get prw", lambda: c["prw"])
t("set pro 5", lambda: c.__setitem__("pro", 5))
t("get pro", lambda: c["pro"])
t("setattr fin", lambda: setattr(c, "fin", 3.0))
t("get fin", lambda: c.fin)
t("setattr newattr", lambda: setattr(c, "zzz", 3.0))
t("get zzz", lambda: c.zzz)
t("set missing item", lambda: c.__setitem__("nope", 1))
t("set fin 'str'", lambda: c.__setitem__("fin", "1.25"))
t("get fin", lambda: c["fin"])
t("set fin None", lambda: c.__setitem__("fin", None))
t("len", lambda: len(c))
t("getprefix", lambda: c.getprefix())
t("setprefix", lambda: c.setprefix("pfx"))
t("newpin with prefix", lambda: c.newpin("q", hal.HAL_BIT, hal.HAL_IN))
t("getitem q", lambda: c["q"])
t("getprefix", lambda: c.getprefix())
t("getpins", lambda: c.getpins())
p = c.newpin("w", hal.HAL_FLOAT, hal.HAL_OUT)
t(
    "pin obj",
    lambda: (
        p,
        p.name,
        p.type,
        p.dir,
        p.value,
        p.get(),
        p.get_name(),
        p.get_type(),
        p.get_dir(),
        p.is_pin(),
    ),
)
t("pin set", lambda: p.set(4.5))
t("pin value", lambda: p.value)
t("pin value set", lambda: setattr(p, "value", 6.5))
t("pin get", lambda: p.get())
t("getitem obj", lambda: c.getitem("w") if hasattr(c, "getitem") else None)
pass
t("ready", lambda: c.ready())
t("ready again", lambda: c.ready())
t("newpin after ready", lambda: c.newpin("late", hal.HAL_BIT, hal.HAL_IN))
t("exists pyc", lambda: hal.component_exists("pyc"))
t("exists nope", lambda: hal.component_exists("nope"))
t("is_ready pyc", lambda: hal.component_is_ready("pyc"))
t("is_ready nope", lambda: hal.component_is_ready("nope"))
t("new_sig f", lambda: hal.new_sig("sf", hal.HAL_FLOAT))
t("new_sig dup", lambda: hal.new_sig("sf", hal.HAL_FLOAT))
t("new_sig badtype", lambda: hal.new_sig("sx", 42))
t("connect", lambda: hal.connect("pyc.fin", "sf"))
t("connect missing pin", lambda: hal.connect("pyc.nope", "sf"))
t("connect missing sig", lambda: hal.connect("pyc.fin", "nosig"))
t("connect type mismatch", lambda: hal.connect("pyc.bout", "sf"))
t("new_sig b", lambda: hal.new_sig("sb", hal.HAL_BIT))
t("connect bout", lambda: hal.connect("pyc.bout", "sb"))
t("pin_has_writer fin", lambda: hal.pin_has_writer("pyc.fin"))
t("pin_has_writer bout", lambda: hal.pin_has_writer("pyc.bout"))
t("pin_has_writer nope", lambda: hal.pin_has_writer("nope"))
t("get_value sig", lambda: hal.get_value("sf"))
t("get_value param", lambda: hal.get_value("pyc.prw"))
t("get_value s32 pin", lambda: hal.get_value("pyc.sio"))
t("get_value u32 pin", lambda: hal.get_value("pyc.uout"))
t("get_value nope", lambda: hal.get_value("nope"))
t("set_p in pin linked", lambda: hal.set_p("pyc.fin", "2.5"))
t("set_p out pin", lambda: hal.set_p("pyc.uout", "5"))
t("set_p io pin", lambda: hal.set_p("pyc.sio", "9"))
t("get sio", lambda: c["sio"])
t("set_p param", lambda: hal.set_p("pyc.prw", "8.5"))
t("set_p ro param", lambda: hal.set_p("pyc.pro", "8"))
t("set_p bad value", lambda: hal.set_p("pyc.prw", "abc"))
t("set_p number", lambda: hal.set_p("pyc.prw", 3))
t("set_p nope", lambda: hal.set_p("nope", "1"))
t("disconnect", lambda: hal.disconnect("pyc.fin"))
t("disconnect again", lambda: hal.disconnect("pyc.fin"))
t("disconnect nope", lambda: hal.disconnect("nope"))
t("get_info_params", lambda: [d for d in hal.get_info_params() if d["NAME"].startswith("pyc")])
t("msg level", lambda: hal.get_msg_level())
t("is_rt etc", lambda: (hal.is_rt, hal.is_sim, hal.is_userspace, hal.is_kernelspace))
t("item ctor", lambda: hal.item())
t("Pin ctor", lambda: hal.Pin(p._item if hasattr(p, "_item") else p))
t("exit", lambda: c.exit())
t("get after exit", lambda: c["sio"])
