# SPDX-License-Identifier: GPL-2.0-or-later
"""Preparing LinuxCNC sample configurations for our HAL (docs/compat.md).

Pure functions, no system access: reading an INI file's text, resolving
``[SECTION]KEY`` / ``[SECTION](KEY)`` for classification, and the rule
that decides, line by line, what is removed (motion controller, trajectory
planner, homing, kinematics, iocontrol, halui, GUIs and everything that
touches their pins or functions), what is rewritten (motmod becomes the
threads it would create; board drivers point at virtual boards; net lines
lose the pins of removed components) and what is kept unchanged.

Every prepared file keeps its line numbers: a removed line becomes a
``#compat:`` comment, so an error at ``file:N`` is line N of the original.
"""

from __future__ import annotations

import re
import shlex
from collections.abc import Callable
from dataclasses import dataclass, field

# ---- INI files ----------------------------------------------------------------


@dataclass
class Ini:
    """An INI file as LinuxCNC reads it: the first value of a key wins for
    [SECTION]KEY substitution; all values are kept (HALFILE repeats)."""

    values: dict[tuple[str, str], list[str]] = field(default_factory=dict)

    def get(self, section: str, key: str) -> str | None:
        v = self.values.get((section, key))
        return v[0] if v else None

    def all(self, section: str, key: str) -> list[str]:
        return list(self.values.get((section, key), []))


def parse_ini(text: str) -> Ini:
    ini = Ini()
    section = ""
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line[0] in "#;":
            continue
        if line.startswith("[") and "]" in line:
            section = line[1 : line.index("]")].strip()
            continue
        if "=" not in line:
            continue
        key, _, value = line.partition("=")
        ini.values.setdefault((section, key.strip()), []).append(value.strip())
    return ini


INCLUDE = re.compile(r"^#INCLUDE\s+(\S+)\s*$")


def expand_includes(text: str, read: Callable[[str], str], depth: int = 0) -> str:
    """LinuxCNC's ``#INCLUDE file`` lines replaced by the file's text."""
    if depth > 10:
        raise ValueError("#INCLUDE nested more than 10 deep")
    out = []
    for line in text.splitlines():
        m = INCLUDE.match(line.strip())
        out.append(expand_includes(read(m.group(1)), read, depth + 1) if m else line)
    return "\n".join(out) + "\n"


INI_REF = re.compile(r"\[([^\]\s]+)\]\(([^)\s]+)\)|\[([^\]\s]+)\]([A-Za-z0-9_]+)")


def resolve(text: str, ini: Ini) -> str:
    """[SECTION]KEY and [SECTION](KEY) replaced by their first value (unknown
    references stay as they are; halcmd reports them)."""

    def sub(m: re.Match[str]) -> str:
        sec, key = (m.group(1), m.group(2)) if m.group(1) else (m.group(3), m.group(4))
        v = ini.get(sec, key)
        return m.group(0) if v is None else v

    return INI_REF.sub(sub, text)


# ---- what belongs to the parts we remove ---------------------------------------

# Realtime modules of the motion controller and its helpers.
MOTION_MODULES = {"motmod", "tpmod", "homemod", "tp"}
# LinuxCNC 2.9's kinematics modules (/usr/lib/linuxcnc/modules); any other
# module whose name ends in "kins" counts too.
KINEMATICS = {
    "5axiskins", "corexykins", "genhexkins", "genserkins", "gantrykins", "lineardeltakins",
    "maxkins", "millturn", "pentakins", "pumakins", "rosekins", "rotarydeltakins",
    "rotatekins", "scarakins", "scorbot-kins", "tripodkins", "trivkins", "userkins",
    "xyzab_tdr_kins", "xyzac-trt-kins", "xyzbc-trt-kins",
}  # fmt: skip
IOCONTROL_PROGRAMS = {"io", "iov2", "iocontrol", "iocontrolv2", "hal_manualtoolchange"}
HALUI_PROGRAMS = {"halui"}
# Programs that drive a USB pendant this project has no virtual device for.
# LinuxCNC's xhc-hb04 fails or waits for its USB device, so the result would
# depend on the machine; the line is rewritten to a program that does not
# exist, so it fails at once, as with no pendant attached (LinuxCNC's
# xhc-hb04.tcl then goes on without the pendant).
PENDANT_PROGRAMS = {"xhc-hb04"}
PENDANT_ABSENT = "xhc-hb04-not-attached"
GUI_PROGRAMS = {
    "pyvcp", "gladevcp", "axis", "touchy", "gmoccapy", "qtvcp", "gscreen", "halscope",
    "halmeter", "halshow", "vismach", "panelui",
}  # fmt: skip
MOTION_FUNCTIONS = {"motion-command-handler", "motion-controller"}
# Pins, parameters and functions of the motion controller (2.9 names).
MOTION_PREFIXES = ("motion.", "axis.", "joint.", "spindle.", "ini.", "tp.", "home.")
IOCONTROL_PREFIXES = ("iocontrol.", "hal_manualtoolchange.")
HALUI_PREFIXES = ("halui.",)
GUI_PREFIXES = ("axisui.", "pyvcp.", "gladevcp.", "gmoccapy.", "touchy.", "qtvcp.")

HAL_COMMANDS_WITH_OBJECTS = {"setp", "getp", "ptype", "unlinkp"}

# The motion stand-in (tests/compat/standin): when a configuration loads
# motmod, compat_motion exports motion's two functions (no-ops) and
# compat_joint the pins joint.N.motor-pos-cmd and joint.N.motor-pos-fb for
# motmod's num_joints (16, motmod's maximum, when the line does not say).
# Lines naming only these objects are kept: LinuxCNC's hookup_moveoff.tcl
# finds motion's functions in `show thread` and reconnects these pins.
STANDIN_MODULES = ("compat_motion", "compat_joint")
STANDIN_JOINT_PIN = re.compile(r"joint\.(\d+)\.motor-pos-(cmd|fb)")
STANDIN_MAX_JOINTS = 16


def is_kinematics(module: str) -> bool:
    return module in KINEMATICS or module.endswith("kins")


@dataclass
class Context:
    """What the lines seen so far removed: prefixes of their HAL objects."""

    prefixes: dict[str, str] = field(
        default_factory=lambda: {
            **{p: "motion" for p in MOTION_PREFIXES},
            **{p: "iocontrol" for p in IOCONTROL_PREFIXES},
            **{p: "halui" for p in HALUI_PREFIXES},
            **{p: "GUI" for p in GUI_PREFIXES},
            **{k + ".": "kinematics" for k in KINEMATICS},
        }
    )
    # components the configuration loads itself: their names are never
    # taken as removed prefixes (a user component called "spindle")
    own: set[str] = field(default_factory=set)
    # programs of the configuration that belong to a removed part
    # (see program_part), by name
    programs: dict[str, str] = field(default_factory=dict)
    # signals only removed lines created, with the part (a later `sets` of
    # one goes too; a kept `net` that creates it again revives it)
    dead_signals: dict[str, str] = field(default_factory=dict)
    # signals a kept line created (a removed net does not make them dead)
    live_signals: set[str] = field(default_factory=set)
    # files `source`d by the configuration's .hal files, already prepared
    prepared_sources: set[str] = field(default_factory=set)
    # joints of the motion stand-in, set by the motmod line (0: no motmod
    # line yet); standin_loaded once the stand-in is in the session
    standin_joints: int = 0
    standin_loaded: bool = False

    def is_standin(self, name: str) -> bool:
        """Whether the motion stand-in has this object."""
        if not self.standin_joints:
            return False
        if name in MOTION_FUNCTIONS:
            return True
        m = STANDIN_JOINT_PIN.fullmatch(name)
        return bool(m) and int(m.group(1)) < self.standin_joints

    def owner(self, name: str) -> str | None:
        """The removed part a pin/param/function name belongs to, or None."""
        if self.is_standin(name):
            return None
        if name in MOTION_FUNCTIONS:
            return "motion"
        for prefix, part in self.prefixes.items():
            if name.startswith(prefix) and prefix[:-1] not in self.own:
                return part
        return None


@dataclass
class Action:
    """What happens to one logical line: kind is keep, remove or rewrite."""

    kind: str
    part: str = ""  # motion, kinematics, iocontrol, halui, GUI, pendant, board
    why: str = ""
    text: str = ""  # the new line for rewrite


KEEP = Action("keep")


def split_words(text: str) -> list[str]:
    """A halcmd line's words, quotes removed."""
    try:
        return shlex.split(text, comments=False, posix=True)
    except ValueError:
        return text.split()


_words = split_words


def _module_names(words: list[str]) -> list[str]:
    """Component names a loadrt line creates (names= or the module name)."""
    for w in words[2:]:
        if w.startswith("names="):
            return [n for n in w[6:].split(",") if n]
    return [words[1]]


def _loadusr_program(words: list[str]) -> tuple[str, str | None]:
    """(program, component name) of a loadusr line: -Wn NAME, -c NAME."""
    i, name = 1, None
    while i < len(words) and words[i].startswith("-"):
        flag = words[i]
        if flag in ("-Wn", "-n") and i + 1 < len(words):
            name = words[i + 1]
            i += 2
            continue
        i += 1
    prog = words[i] if i < len(words) else ""
    rest = words[i + 1 :]
    for j, w in enumerate(rest[:-1]):
        if w == "-c":
            name = name or rest[j + 1]
    base = prog.rsplit("/", 1)[-1]
    if base in ("python", "python3") and rest:
        base = rest[0].rsplit("/", 1)[-1]
    return base, name


VISMACH = re.compile(r"^\s*(import|from)\s+vismach\b", re.M)
LINUXCNC_MODULE = re.compile(r"^\s*import\s+([\w, ]*\b)?linuxcnc\b", re.M)


def program_part(text: str) -> str | None:
    """The removed part a program of a configuration belongs to, from its
    source: a vismach machine view is a GUI; a program that imports the
    `linuxcnc` module talks to LinuxCNC's task and motion controller."""
    if not text.startswith("#!"):
        return None
    if VISMACH.search(text):
        return "GUI"
    if LINUXCNC_MODULE.search(text):
        return "motion"
    return None


def motmod_threads(orig_words: list[str], res_words: list[str]) -> str:
    """The threads line for a motmod line: base-thread (no floating point)
    when base_period_nsec is given and not 0, servo-thread (floating point),
    with the periods as written (INI references left for halcmd -i)."""
    period: dict[str, str] = {}
    for o, r in zip(orig_words, res_words):
        for key in ("base_period_nsec", "servo_period_nsec"):
            if r.startswith(key + "="):
                period[key] = (o if o.startswith(key + "=") else r).split("=", 1)[1]
                period[key + "/resolved"] = r.split("=", 1)[1]
    threads = []
    base = period.get("base_period_nsec/resolved", "0")
    if base not in ("", "0"):
        threads.append(("base-thread", period["base_period_nsec"], 0))
    threads.append(("servo-thread", period.get("servo_period_nsec", "1000000"), 1))
    args = " ".join(
        f"name{i}={n} period{i}={p} fp{i}={fp}" for i, (n, p, fp) in enumerate(threads, 1)
    )
    return f"loadrt threads {args}"


def motmod_joints(res_words: list[str]) -> int:
    """The motion stand-in's joints for a motmod line (its words with INI
    values substituted): num_joints, STANDIN_MAX_JOINTS when missing or not
    a number."""
    for w in res_words:
        if w.startswith("num_joints=") and w[11:].isdigit():
            return max(1, min(int(w[11:]), STANDIN_MAX_JOINTS))
    return STANDIN_MAX_JOINTS


def standin_lines(joints: int) -> list[str]:
    """The HAL lines that load the motion stand-in with this many joints."""
    names = ",".join(f"joint.{i}" for i in range(joints))
    return [
        f"loadrt {STANDIN_MODULES[0]} names={','.join(sorted(MOTION_FUNCTIONS))}",
        f"loadrt {STANDIN_MODULES[1]} names={names}",
    ]


ARROWS = ("=>", "<=", "<=>")


def _rewrite_net(orig: list[str], res: list[str], ctx: Context) -> Action:
    """net SIG [arrow] pin ...: drop removed pins with the arrow before them."""
    items: list[tuple[str | None, str, str]] = []  # (arrow before, pin, resolved pin)
    arrow: str | None = None
    for o, r in zip(orig[2:], res[2:]):
        if r in ARROWS:
            arrow = o
        else:
            items.append((arrow, o, r))
            arrow = None
    dropped = [(r, part) for _, _, r in items if (part := ctx.owner(r))]
    if not dropped:
        return KEEP
    part = "/".join(sorted({p for _, p in dropped}))
    names = ", ".join(r for r, _ in dropped)
    kept = [(a, o) for a, o, r in items if not ctx.owner(r)]
    if not kept:
        if res[1] not in ctx.live_signals:
            ctx.dead_signals.setdefault(res[1], part)
        return Action("remove", part, f"net of {names} only")
    words = orig[:2] + [w for a, o in kept for w in ((a, o) if a else (o,))]
    return Action("rewrite", part, f"without {names}", " ".join(words))


def classify(line: str, ini: Ini, ctx: Context) -> Action:
    """The action for one logical line (comments and blank lines are kept)."""
    body = line.split("#", 1)[0].strip() if not line.lstrip().startswith("#") else ""
    if not body:
        return KEEP
    orig = body.split()
    res = [resolve(w, ini) for w in orig]
    cmd = res[0]
    flat = _words(" ".join(res))
    if cmd == "loadrt" and len(flat) > 1:
        mod = flat[1]
        # the module named by a missing INI key keeps its role
        missing = INI_REF.fullmatch(mod)
        if missing and (missing.group(2) or missing.group(4)) == "KINEMATICS":
            return Action("remove", "kinematics", f"loadrt {mod} (no such INI value)")
        if mod == "motmod":
            ctx.standin_joints = ctx.standin_joints or motmod_joints(flat)
            return Action(
                "rewrite",
                "motion",
                "motmod replaced by the threads it creates",
                motmod_threads(orig, res),
            )
        if mod in MOTION_MODULES:
            return Action("remove", "motion", f"loadrt {mod}")
        if is_kinematics(mod):
            for name in _module_names(flat):
                ctx.prefixes[name + "."] = "kinematics"
            return Action("remove", "kinematics", f"loadrt {mod}")
        ctx.own.update(_module_names(flat))
        return KEEP
    if cmd == "loadusr" and len(flat) > 1:
        prog, name = _loadusr_program(flat)
        part = ctx.programs.get(prog)
        if part:
            pass
        elif prog in IOCONTROL_PROGRAMS:
            part = "iocontrol"
        elif prog in HALUI_PROGRAMS:
            part = "halui"
        elif prog in PENDANT_PROGRAMS:
            for n in {prog, name or prog}:
                ctx.prefixes[n + "."] = "pendant"
            return Action(
                "rewrite", "pendant", "no USB pendant attached", f"loadusr -W {PENDANT_ABSENT}"
            )
        elif prog in GUI_PROGRAMS or prog.endswith("gui"):
            part = "GUI"
        if part:
            for n in {prog, name or prog}:
                ctx.prefixes[n + "."] = part
            return Action("remove", part, f"loadusr {prog}")
        ctx.own.add(name or prog)
        return KEEP
    if cmd == "addf" and len(flat) > 1:
        part = ctx.owner(flat[1])
        return Action("remove", part, f"addf {flat[1]}") if part else KEEP
    if cmd == "net" and len(orig) > 2:
        action = _rewrite_net(orig, res, ctx)
        if action.kind != "remove":
            ctx.dead_signals.pop(res[1], None)
            ctx.live_signals.add(res[1])
        return action
    if cmd == "newsig" and len(flat) > 1:
        ctx.dead_signals.pop(flat[1], None)
        ctx.live_signals.add(flat[1])
        return KEEP
    if cmd in ("sets", "gets", "stype", "delsig") and len(flat) > 1 and flat[1] in ctx.dead_signals:
        return Action("remove", ctx.dead_signals[flat[1]], f"{cmd} {flat[1]} (its net was removed)")
    if cmd == "delsig" and len(flat) > 1:
        ctx.live_signals.discard(flat[1])
        return KEEP
    if cmd in HAL_COMMANDS_WITH_OBJECTS and len(flat) > 1:
        part = ctx.owner(flat[1])
        return Action("remove", part, f"{cmd} {flat[1]}") if part else KEEP
    if cmd in ("linksp", "linkps", "linkpp", "alias") and len(flat) > 2:
        names = flat[1:] if cmd != "alias" else flat[2:3]
        for n in names:
            part = ctx.owner(n)
            if part:
                return Action("remove", part, f"{cmd} {n}")
    return KEEP


# ---- files -------------------------------------------------------------------


@dataclass
class Prepared:
    """A prepared HAL file and what was done to it."""

    text: str
    actions: list[tuple[int, Action]] = field(default_factory=list)  # (line, action)

    def count(self, kind: str) -> dict[str, int]:
        out: dict[str, int] = {}
        for _, a in self.actions:
            if a.kind == kind:
                out[a.part] = out.get(a.part, 0) + 1
        return out


def logical_lines(text: str) -> list[tuple[int, int, str]]:
    """(first line, last line, joined text) of each logical line (backslash
    continuation joins with no space, as LinuxCNC's halcmd does)."""
    out = []
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        first, joined = i, ""
        while True:
            cur = lines[i]
            if cur.endswith("\\") and i + 1 < len(lines):
                joined += cur[:-1]
                i += 1
                continue
            joined += cur
            break
        out.append((first + 1, i + 1, joined))
        i += 1
    return out


LineHook = Callable[[int, str, list[str], "Action"], "Action"]


def prepare(text: str, ini: Ini, ctx: Context, hook: LineHook | None = None) -> Prepared:
    """The file with removed lines commented out and rewritten lines in
    place (a rewritten continued line takes its first physical line; the
    others become comments).  `hook(first_line, text, resolved_words,
    action)` may turn a kept line into a rewrite (virtual boards)."""
    lines = text.split("\n")
    prep = Prepared("")
    for first, last, joined in logical_lines(text):
        action = classify(joined, ini, ctx)
        if hook and action.kind == "keep":
            body = joined.split("#", 1)[0].strip()
            if body:
                action = hook(first, joined, _words(resolve(body, ini)), action)
        if action.kind == "keep":
            if action.why:  # a note (no virtual board for this one)
                prep.actions.append((first, action))
            continue
        prep.actions.append((first, action))
        if action.kind == "remove":
            new = [f"#compat: removed ({action.part}: {action.why})"]
        else:
            new = [f"{action.text}  #compat: {action.part}: {action.why}"]
        new += ["#compat: (continued)"] * (last - first)
        lines[first - 1 : last] = new
    prep.text = "\n".join(lines)
    return prep


# ---- TWOPASS ------------------------------------------------------------------


def twopass_merge(loadrt_lines: list[list[str]]) -> list[str]:
    """LinuxCNC's TWOPASS: every loadrt of a module becomes one line; count=
    values add up and names= lists join; a repeated line without them is
    loaded once.  Input: the resolved words of each loadrt line in order."""
    merged: dict[str, dict[str, list[str]]] = {}
    order: list[str] = []
    for words in loadrt_lines:
        mod = words[1]
        entry = merged.setdefault(mod, {"count": [], "names": [], "other": []})
        if mod not in order:
            order.append(mod)
        for w in words[2:]:
            if w.startswith("count="):
                entry["count"].append(w[6:])
            elif w.startswith("names="):
                entry["names"] += [n for n in w[6:].split(",") if n]
            elif w not in entry["other"]:
                entry["other"].append(w)
    out = []
    for mod in order:
        e = merged[mod]
        args = list(e["other"])
        if e["names"]:
            args.append("names=" + ",".join(e["names"]))
        elif e["count"]:
            args.append(f"count={sum(int(c, 0) for c in e['count'])}")
        out.append(" ".join(["loadrt", mod, *args]))
    return out
