# SPDX-License-Identifier: GPL-2.0-or-later
"""The parsed form of a .comp file: what the declaration section says."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

# HAL types a pin or parameter may have, and their spellings in .comp files.
HAL_TYPES = {
    "bit": "bit",
    "float": "float",
    "signed": "s32",
    "s32": "s32",
    "unsigned": "u32",
    "u32": "u32",
    "s64": "s64",
    "u64": "u64",
}
PIN_DIRS = ("in", "out", "io")
PARAM_DIRS = ("r", "rw")

# Options with their meaning; any other name is accepted with a warning
# (the seed: "the result of using any other option is undefined").
KNOWN_OPTIONS = {
    "singleton",
    "default_count",
    "count_function",
    "rtapi_app",
    "data",
    "extra_setup",
    "extra_cleanup",
    "userspace",
    "userinit",
    "constructable",
    "period",
    "personality",
    "homemod",
    "extra_compile_args",
    "extra_link_args",
    "fp",
}


@dataclass(frozen=True)
class Pos:
    """A place in a source file, 1-based line and column."""

    file: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.col}"


@dataclass
class Item:
    """A pin or a parameter."""

    kind: str  # "pin" or "param"
    dir: str  # in/out/io or r/rw
    type: str  # bit/float/s32/u32/s64/u64
    name: str  # HALNAME as written ("out-#", "sin_")
    pos: Pos
    size: int = 0  # 0: scalar; else the (maximum) array size
    condsize: str | None = None  # C expression: the array size for an instance
    cond: str | None = None  # C expression: create only when nonzero
    default: str | None = None  # C expression
    doc: str = ""

    @property
    def is_array(self) -> bool:
        return self.size > 0


@dataclass
class Function:
    name: str  # HALNAME; "_" means "named like the instance"
    pos: Pos
    fp: bool = True
    doc: str = ""


@dataclass
class Variable:
    ctype: str  # "double", "unsigned int", "hal_float_t"
    name: str  # C identifier, with its leading stars removed
    stars: str  # "" or "*", "**", ...
    pos: Pos
    size: int = 0
    default: str | None = None


@dataclass
class ModParam:
    ctype: str  # int, long, string
    name: str
    pos: Pos
    default: str | None = None
    doc: str = ""


@dataclass
class Component:
    name: str
    pos: Pos
    doc: str = ""
    items: list[Item] = field(default_factory=list)
    functions: list[Function] = field(default_factory=list)
    variables: list[Variable] = field(default_factory=list)
    modparams: list[ModParam] = field(default_factory=list)
    options: dict[str, str] = field(default_factory=dict)
    option_pos: dict[str, Pos] = field(default_factory=dict)
    includes: list[str] = field(default_factory=list)
    license: str = ""
    authors: list[str] = field(default_factory=list)
    description: str = ""
    notes: list[str] = field(default_factory=list)
    see_also: list[str] = field(default_factory=list)
    examples: list[str] = field(default_factory=list)
    code: str = ""  # the C after ";;"
    code_line: int = 0  # line number of the first line of `code`
    source: Path = Path()

    def option(self, name: str) -> bool:
        """True when `option NAME` is given with a yes-like value."""
        v = self.options.get(name)
        return v is not None and v.lower() not in ("no", "0", "false")

    @property
    def userspace(self) -> bool:
        return self.option("userspace")

    @property
    def has_personality(self) -> bool:
        if self.option("personality"):
            return True
        return any(i.cond is not None or i.condsize is not None for i in self.items)
