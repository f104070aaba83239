# SPDX-License-Identifier: GPL-2.0-or-later
"""``halcompile --print-modinfo``: what loading the component offers, one
fact per line (name, kind, license, author, description, module parameters,
pins, parameters, functions)."""

from __future__ import annotations

from .model import Component
from .names import comp_prefix, hal_name


def modinfo(c: Component) -> str:
    L = [f"name: {c.name}", f"kind: {'userspace' if c.userspace else 'realtime'}"]
    L.append(f"prefix: {comp_prefix(c.name)}")
    L.append(f"license: {c.license}")
    for a in c.authors:
        L.append(f"author: {a}")
    if c.doc:
        L.append(f"description: {c.doc}")
    if not c.userspace:
        if not (c.option("singleton") or c.option("count_function")):
            L.append("parm: count:number of instances (int)")
            L.append("parm: names:names of instances (array of charp)")
        if c.has_personality:
            L.append("parm: personality:personality of each instance (array of int)")
    for m in c.modparams:
        if m.ctype != "dummy":
            t = "charp" if m.ctype == "string" else m.ctype
            L.append(f"parm: {m.name}:{m.doc} ({t})")
    for it in c.items:
        size = f"[{it.size}]" if it.is_array else ""
        L.append(f"{it.kind}: {hal_name(it.name)}{size} {it.type} {it.dir}")
    for f in c.functions:
        L.append(f"function: {hal_name(f.name) or '_'} {'fp' if f.fp else 'nofp'}")
    return "\n".join(L) + "\n"
