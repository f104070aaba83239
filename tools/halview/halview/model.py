# SPDX-License-Identifier: GPL-2.0-or-later
"""A snapshot of everything in HAL, for halshow's tree and the web page.

Objects come from libhalview in halcmd's show order; each carries the facts
halcmd's show prints (type, direction, value, links, owner).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

from . import halapi
from .halapi import HalError


@dataclass
class Item:
    kind: str  # comp, pin, param, sig, funct, thread
    name: str
    type: str = ""
    dir: str = ""
    value: str = ""
    links: list[str] = field(default_factory=list)  # signal of a pin; pins of a signal
    owner: str = ""
    extra: dict[str, str] = field(default_factory=dict)

    def to_json(self) -> dict[str, object]:
        return asdict(self)


def _item(kind: int, name: str) -> Item | None:
    f = halapi.info(kind, name)
    if f is None:
        return None
    k = halapi.KIND_NAMES[kind]
    if kind == halapi.PIN:
        return Item(k, name, f[0], f[1], f[2], [f[3]] if f[3] else [], f[4])
    if kind == halapi.PARAM:
        return Item(k, name, f[0], f[1], f[2], [], f[3])
    if kind == halapi.SIG:
        pins = f[5].split() if len(f) > 5 and f[5] else []
        return Item(
            k, name, f[0], "", f[1], pins, extra={"writers": f[2], "readers": f[3], "bidirs": f[4]}
        )
    if kind == halapi.COMP:
        extra = {"id": f[0], "rt": f[1], "pid": f[2], "ready": f[3], "args": f[4]}
        return Item(k, name, "RT" if f[1] == "1" else "User", extra=extra)
    if kind == halapi.FUNCT:
        extra = {"owner_id": f[0], "fp": f[1], "reentrant": f[2], "users": f[3]}
        return Item(k, name, extra=extra)
    extra = {"period": f[0], "fp": f[1]}
    return Item(k, name, links=f[2].split() if len(f) > 2 and f[2] else [], extra=extra)


KINDS = (halapi.COMP, halapi.PIN, halapi.PARAM, halapi.SIG, halapi.FUNCT, halapi.THREAD)


def snapshot(pattern: str = "") -> dict[str, list[Item]]:
    """Every object whose name matches (prefix or glob), per kind."""
    out: dict[str, list[Item]] = {}
    for kind in KINDS:
        items = []
        for name in halapi.list_names(kind, pattern):
            it = _item(kind, name)
            if it is not None:  # removed while we looked
                items.append(it)
        out[halapi.KIND_NAMES[kind]] = items
    return out


def lookup(kind: str, name: str) -> Item | None:
    if kind not in halapi.KIND_BY_NAME:
        raise HalError(f"unknown kind '{kind}' (comp, pin, param, sig, funct, thread)")
    return _item(halapi.KIND_BY_NAME[kind], name)


def parse_item(spec: str) -> tuple[int, str]:
    """KIND NAME as halmeter takes it, pin+NAME as halshow's watch files
    hold it, or a bare NAME (looked up: pin, signal, parameter)."""
    for sep in ("+", ":"):
        if sep in spec:
            k, _, n = spec.partition(sep)
            if k in ("pin", "sig", "signal", "param", "parameter"):
                return halapi.KIND_BY_NAME[k], n
    return halapi.find_kind(spec), spec


def set_item(kind: int, name: str, value: str) -> str:
    """setp/sets with halcmd's rules; returns the value now read back."""
    halapi.set_value(kind, name, value)
    return halapi.get(kind, name)
