# SPDX-License-Identifier: GPL-2.0-or-later
"""HALNAME conversions (seed: "Comp HAL Component Generator", Syntax).

HAL identifier: underscores become dashes, a trailing dash or period is
removed ("this_name_" -> "this-name"), "_" alone is the empty name (function
"_" is named like the instance).  Each block of '#' is an array index,
zero-padded to the number of '#'.

C identifier: every '#' and any '.', '_' or '-' right before it are removed,
remaining '.' and '-' become '_', runs of '_' collapse to one; a trailing
'_' stays ("min_" stays usable next to min()).
"""

from __future__ import annotations

import re


def hal_name(name: str) -> str:
    """The HAL form of a pin, param or function HALNAME (with '#' kept)."""
    if name == "_":
        return ""
    return name.replace("_", "-").rstrip("-.")


def c_name(name: str) -> str:
    s = re.sub(r"[._-]*#+", "", name)
    s = s.replace(".", "_").replace("-", "_")
    return re.sub(r"__+", "_", s)


def comp_prefix(comp_name: str) -> str:
    """Default instance prefix: the component name without a leading 'hal_',
    underscores as dashes ("conv_bit_float" -> "conv-bit-float")."""
    base = comp_name[4:] if comp_name.startswith("hal_") else comp_name
    return base.replace("_", "-")


def hash_blocks(name: str) -> int:
    return len(re.findall(r"#+", name))


def expand(name: str, index: int) -> str:
    """The HAL name of array element `index` of a HAL name with '#'."""

    def rep(m: re.Match[str]) -> str:
        return f"{index:0{len(m.group(0))}d}"

    return re.sub(r"#+", rep, name, count=1)
