# SPDX-License-Identifier: GPL-2.0-or-later
"""Userspace HAL components in Python, and HAL inspection by name.

    import hal, time
    h = hal.component("passthrough")
    h.newpin("in", hal.HAL_FLOAT, hal.HAL_IN)
    h.newpin("out", hal.HAL_FLOAT, hal.HAL_OUT)
    h.ready()
    try:
        while True:
            time.sleep(0.01)
            h["out"] = h["in"]          # or h.out = h.in_ ... see docs
    except KeyboardInterrupt:
        pass

`halcmd unload` / `unloadusr` ends such a component with SIGTERM, which
this module turns into KeyboardInterrupt (as LinuxCNC's does).  The API
follows LinuxCNC 2.9's `hal` module; see docs/hal-python.md for the
details and the few extensions (HAL_S64/HAL_U64, set_s, no need for a
component before the module-level helpers).
"""

import signal as _signal

import _hal
from _hal import *  # noqa: F401,F403  (the C API is the public API)


class _ItemWrap:
    """Attribute-style access (name, type, dir, value) around a _hal.item."""

    def __new__(cls, item):
        if not isinstance(item, _hal.item):
            raise TypeError("Constructor argument must be _hal.item: %s" % type(item))
        self = super().__new__(cls)
        self._item = item
        for f in ("get", "set", "get_type", "get_name", "get_dir", "is_pin"):
            setattr(self, f, getattr(item, f))
        return self

    def __init__(self, item):
        self._item = item

    name = property(lambda s: s._item.get_name())
    type = property(lambda s: s._item.get_type())
    dir = property(lambda s: s._item.get_dir())
    value = property(lambda s: s._item.get(), lambda s, v: s._item.set(v))


class Pin(_ItemWrap):
    def __init__(self, item):
        _ItemWrap.__init__(self, item)
        if not item.is_pin():
            raise TypeError("Must be constructed from pin object")


class Param(_ItemWrap):
    def __init__(self, item):
        _ItemWrap.__init__(self, item)
        if item.is_pin():
            raise TypeError("Must be constructed from param object")


def _sigterm_to_keyboard_interrupt(signum, frame):
    raise KeyboardInterrupt


class component(_hal.component):
    """A userspace HAL component: component(name, prefix=name)."""

    def __init__(self, *args, **kw):
        _hal.component.__init__(self, *args, **kw)
        # halcmd unload/unloadusr send SIGTERM: end the main loop the same
        # way Ctrl-C does.  Only the main thread may install handlers.
        try:
            if _signal.getsignal(_signal.SIGTERM) in (_signal.SIG_DFL, None):
                _signal.signal(_signal.SIGTERM, _sigterm_to_keyboard_interrupt)
        except ValueError:
            pass

    def newpin(self, *a, **kw):
        return Pin(_hal.component.newpin(self, *a, **kw))

    def newparam(self, *a, **kw):
        return Param(_hal.component.newparam(self, *a, **kw))

    def getpin(self, *a, **kw):
        return Pin(_hal.component.getitem(self, *a, **kw))

    def getparam(self, *a, **kw):
        return Param(_hal.component.getitem(self, *a, **kw))

    def getpins(self, *a, **kw):
        return _hal.component.getpins(self, *a, **kw)
