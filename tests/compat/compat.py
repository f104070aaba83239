# SPDX-License-Identifier: GPL-2.0-or-later
"""`make compat`: LinuxCNC 2.9's sample configurations on our HAL (docs/compat.md).

For every INI file of the chosen sample configurations: copy the
configuration into a temporary directory, prepare its [HAL] HALFILEs and
HALCMDs with halprep (motion, kinematics, iocontrol, halui and GUI lines
removed; boards pointed at virtual boards), start the virtual boards and
parallel ports it needs, and run every file by its own program in one HAL
session on the simulated clock, as LinuxCNC does (`halcmd -k -i INI -f` for
a .hal file; haltcl for a .tcl file, with the same rule applied to each
HAL command it makes, see tclfilter.py), followed by 100 ms of simulated
time.  A file is *loaded* when none of its lines failed.  The report (Markdown, also JSON) lists each file's
result; the exit status is 1 when any file failed.

The sample configurations are LinuxCNC's files: they are read from
/usr/share/doc/linuxcnc/examples/sample-configs at run time and never
copied into this tree.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(ROOT / "tests" / "common"))
import halprep  # noqa: E402
import session  # noqa: E402
import tclfilter  # noqa: E402
import vboard  # noqa: E402

SAMPLES = Path("/usr/share/doc/linuxcnc/examples/sample-configs")
HALLIB = session.HALLIB
DEFAULT_SETS = [
    "by_interface/mesa/hm2-*",
    "by_interface/pluto",
    "by_interface/parport",
    "by_machine/smithy",
    "sim",
]
# local-bus virtual boards, by the firmware directory their firmware is in
# (hm2/<dir>/; the gate-size variants 5i22-1, 5i22-1.5, 3x20-1 are boards
# of their own)
VIRTUAL_BOARDS = {"5i20", "5i22-1", "5i22-1.5", "5i23", "5i25", "3x20-1", "4i65", "4i68"}
RUN_NS = "100ms"
ERROR_LINE = re.compile(r"^(?P<file>[^\s:][^:]*):(?P<line>\d+): (?P<msg>.*)$")


def build_dir() -> Path:
    return Path(os.environ.get("HM_BUILD", str(ROOT / "build")))


# ---- results ----------------------------------------------------------------


@dataclass
class FileResult:
    name: str  # as the INI names it (LIB:x.hal, sub/x.hal, HALCMD)
    status: str = "loaded"  # loaded, failed, not run
    first_error: str = ""  # file:line: message
    context: str = ""  # the messages printed just before it
    errors: int = 0
    causes: list[str] = field(default_factory=list)  # every failing line's cause, classified
    removed: dict[str, int] = field(default_factory=dict)
    rewritten: dict[str, int] = field(default_factory=dict)
    note: str = ""


@dataclass
class ConfigResult:
    ini: str
    files: list[FileResult] = field(default_factory=list)
    postgui: list[str] = field(default_factory=list)
    run_error: str = ""
    hardware: list[str] = field(default_factory=list)
    seconds: float = 0.0

    @property
    def ok(self) -> bool:
        """Everything present loaded (a file the package lacks is not ours)."""
        return not self.run_error and all(f.status in ("loaded", "absent") for f in self.files)


# ---- virtual hardware -------------------------------------------------------


class Hardware:
    """Virtual boards and parallel ports a configuration asks for; the hook
    halprep.prepare calls for every kept line rewrites driver lines."""

    def __init__(self, tmp: Path) -> None:
        self.tmp = tmp
        self.boards: list[vboard.VBoardProcess] = []
        self.used: list[str] = []
        self.ports = 0

    def board(self, kind: str) -> Path:
        sock = self.tmp / f"vb{len(self.boards)}.sock"
        self.boards.append(
            vboard.VBoardProcess(sock, kind, None, (), build_dir() / "bin" / "vboard")
        )
        self.used.append(f"vboard {kind}")
        return sock

    def vport(self) -> Path:
        path = self.tmp / f"pp{self.ports}"
        self.ports += 1
        subprocess.run(
            [str(build_dir() / "bin" / "vparport"), "create", str(path)], check=True, timeout=30
        )
        self.used.append("vparport")
        return path

    def stop(self) -> None:
        for b in self.boards:
            try:
                b.stop()
            except Exception:  # a board that hangs on exit must not stop the run
                b.kill()

    def hook(
        self, line: int, text: str, words: list[str], action: halprep.Action
    ) -> halprep.Action:
        if len(words) < 2 or words[0] != "loadrt":
            return action
        mod, args = words[1], words[2:]
        if mod == "hm2_pci":
            return self._hm2_pci(args, action)
        if mod == "hm2_7i43":
            # the 200K board for a 200K firmware (hm2/7i43-2/), else the 400K
            small = any("firmware=hm2/7i43-2/" in a for a in args)
            sock = self.board("7i43-2" if small else "7i43")
            keep = [a for a in args if not a.startswith(("ioaddr", "port="))]
            return _rewrite(["loadrt", "hm2_7i43", f"port=sim:{sock}", *keep], "7i43 on vboard")
        if mod == "hm2_7i90":
            # the 7i90 runs the firmware of its flash (the virtual one SVST8_4)
            sock = self.board("7i90")
            keep = [a for a in args if not a.startswith(("ioaddr", "port="))]
            return _rewrite(["loadrt", "hm2_7i90", f"port=sim:{sock}", *keep], "7i90 on vboard")
        if mod in ("pluto_servo", "pluto_step"):
            sock = self.board("pluto")
            keep = [a for a in args if not a.startswith(("ioaddr", "port="))]
            return _rewrite(["loadrt", mod, f"port=sim:{sock}", *keep], "Pluto-P on vboard")
        if mod == "hal_parport":
            return self._parport(args, action)
        return action

    def _hm2_pci(self, args: list[str], action: halprep.Action) -> halprep.Action:
        config = next((a[7:] for a in args if a.startswith("config=")), "")
        m = re.search(r"firmware=hm2/([^/\s]+)/", config)
        board = m.group(1) if m else ""
        if board not in VIRTUAL_BOARDS:
            return halprep.Action("keep", why=f"no virtual board for '{board or 'unknown board'}'")
        sock = self.board(board)
        keep = [a for a in args if not a.startswith("config=")]
        return _rewrite(
            ["loadrt", "hm2_sim", f"socket={sock}", f"board={board}", *keep, f"config={config}"],
            f"{board} on vboard",
        )

    def _parport(self, args: list[str], action: halprep.Action) -> halprep.Action:
        cfg = next((a[4:] for a in args if a.startswith("cfg=")), None)
        if cfg is None:
            return action
        out = []
        for tok in cfg.split():
            out.append(tok if tok in ("in", "out", "epp", "x") else f"sim:{self.vport()}")
        keep = [a for a in args if not a.startswith("cfg=")]
        return _rewrite(
            ["loadrt", "hal_parport", *keep, "cfg=" + " ".join(out)], "virtual parallel ports"
        )


def _quoted(key: str, value: str) -> str:
    return f'{key}="{value}"'


def _requote(arg: str) -> str:
    """key=value with blanks in the value, quoted again for halcmd."""
    key, eq, value = arg.partition("=")
    return _quoted(key, value) if eq and any(c.isspace() for c in value) else arg


def _rewrite(words: list[str], why: str) -> halprep.Action:
    return halprep.Action("rewrite", "board", why, " ".join(_requote(w) for w in words))


# ---- one configuration ------------------------------------------------------


def _copy_config(ini_path: Path, work: Path) -> None:
    work.mkdir(parents=True)
    for p in ini_path.parent.iterdir():
        if p.is_file():
            shutil.copy2(p, work / p.name)


def _source_file(name: str, cfgdir: Path, work: Path) -> tuple[Path | None, Path]:
    """(original file, where the prepared copy goes) for a HALFILE name."""
    if name.startswith("LIB:"):
        return (HALLIB / name[4:], work / "hallib" / name[4:])
    src = Path(name) if os.path.isabs(name) else cfgdir / name
    dst = work / os.path.normpath(name).lstrip("/")
    if not src.exists() and (HALLIB / name).exists():
        return (HALLIB / name, dst)  # LinuxCNC looks in its HAL library next
    return (src if src.exists() else None, dst)


@dataclass
class Step:
    """One HALFILE (or the HALCMD lines) and how it runs: a .hal file
    prepared and run by halcmd, a .tcl file run by haltcl with the rule
    applied to its commands as they come."""

    fr: FileResult
    kind: str  # hal, tcl, halcmd
    src: Path | None = None  # the original file
    dst: Path | None = None  # the prepared copy (hal, halcmd)
    args: list[str] = field(default_factory=list)  # HALFILE arguments (tcl)
    prepared: bool = False


def _plan(res: ConfigResult, ini: halprep.Ini, cfgdir: Path, work: Path) -> list[Step]:
    """The configuration's HALFILEs and HALCMD lines in LinuxCNC's order."""
    steps = []
    for entry in ini.all("HAL", "HALFILE"):
        if not entry.split():
            continue  # an empty HALFILE= names nothing
        name, *args = entry.split()
        fr = FileResult(name)
        res.files.append(fr)
        src, dst = _source_file(name, cfgdir, work)
        if src is None:
            fr.status = "absent"
            fr.first_error = f"{name}: not in LinuxCNC's package either (LinuxCNC fails here too)"
            continue
        steps.append(Step(fr, "tcl" if src.suffix == ".tcl" else "hal", src, dst, args))
    cmds = ini.all("HAL", "HALCMD")
    if cmds:
        fr = FileResult("HALCMD")
        res.files.append(fr)
        steps.append(Step(fr, "halcmd", None, work / "compat-halcmd.hal"))
    return steps


def _context_for(cfgdir: Path) -> halprep.Context:
    """The rule's context, knowing which programs of the configuration
    belong to a removed part."""
    ctx = halprep.Context()
    for p in sorted(cfgdir.iterdir()):
        if p.is_file() and p.stat().st_size < 1 << 20:
            part = halprep.program_part(p.read_text(errors="replace"))
            if part:
                ctx.programs[p.name] = part
    return ctx


def _prepare_sourced(
    text: str, ini: halprep.Ini, ctx: halprep.Context, hw: Hardware, work: Path, fr: FileResult
) -> None:
    """Prepare in place the configuration's files that `source` lines of
    TEXT name (halcmd runs in work, so a relative name is there), each once,
    before the file that sources them; their actions count for FR."""
    for line in text.splitlines():
        words = halprep.split_words(line.split("#", 1)[0])
        if len(words) != 2 or words[0] != "source":
            continue
        path = (work / halprep.resolve(words[1], ini)).resolve()
        if not path.is_relative_to(work.resolve()) or not path.is_file():
            continue
        if str(path) in ctx.prepared_sources:
            continue
        ctx.prepared_sources.add(str(path))
        inner = path.read_text(errors="replace")
        _prepare_sourced(inner, ini, ctx, hw, work, fr)
        prep = halprep.prepare(inner, ini, ctx, hw.hook)
        for kind, counts in (("remove", fr.removed), ("rewrite", fr.rewritten)):
            for part, n in prep.count(kind).items():
                counts[part] = counts.get(part, 0) + n
        path.write_text(prep.text)


def _prepare(step: Step, ini: halprep.Ini, ctx: halprep.Context, hw: Hardware, work: Path) -> str:
    """Write the prepared copy of a .hal step (and of the files it
    sources); its path relative to work."""
    assert step.dst is not None
    if step.kind == "halcmd":
        text = "\n".join(ini.all("HAL", "HALCMD")) + "\n"
    else:
        assert step.src is not None
        text = step.src.read_text(errors="replace")
    fr = step.fr
    fr.removed, fr.rewritten = {}, {}
    _prepare_sourced(text, ini, ctx, hw, work, fr)
    prep = halprep.prepare(text, ini, ctx, hw.hook)
    for kind, counts in (("remove", fr.removed), ("rewrite", fr.rewritten)):
        for part, n in prep.count(kind).items():
            counts[part] = counts.get(part, 0) + n
    fr.note = "; ".join(a.why for _, a in prep.actions if a.kind == "keep" and a.why)
    step.dst.parent.mkdir(parents=True, exist_ok=True)
    step.dst.write_text(prep.text)
    step.prepared = True
    return str(step.dst.relative_to(work))


INFORMATIVE = re.compile(
    r"not found|cannot|can't|failed|error|unknown|invalid|no such|missing", re.I
)


def _context(recent: list[str]) -> str:
    """The messages that explain a failure: those that say what went wrong
    (at most three), else the last one."""
    picked = [ln for ln in recent if INFORMATIVE.search(ln)][-3:]
    return " / ".join(picked or recent[-1:])


INI_FORM = re.compile(r"(\[[^\]\s]+\]\([^)\s]+\))")
CAUSES = [
    (re.compile(r"(\S+): dlopen: \S+\.so: cannot open shared object file"), "component {0}"),
    (re.compile(r"firmware (\S+) not found"), "firmware {0}"),
    (re.compile(r"Can't find program '([^']+)'"), "program {0}"),
    (re.compile(r"(Unknown parameter `[^']*')"), "{0}"),
]
CONSEQUENCE = re.compile(r"not found|does not exist")


def _cause(line: str, context: str) -> str:
    """What a failing line says is missing, in a few words."""
    m = INI_FORM.search(line) or INI_FORM.search(context)
    if m:
        return f"halcmd: INI substitution {m.group(1)} (the [SECTION](KEY) form)"
    for rx, fmt in CAUSES:
        m = rx.search(context) or rx.search(line)
        if m:
            return fmt.format(*m.groups())
    if CONSEQUENCE.search(line) or CONSEQUENCE.search(context):
        return "a pin, parameter, signal or function that does not exist (often a consequence)"
    return "halcmd: " + re.sub(r"'[^']*'", "'…'", re.sub(r"^\S+:\d+: ", "", line))


def _parse_output(out: str, fr: FileResult) -> None:
    """Every `FILE:LINE: message` line a step printed counts against its
    file (a file it sources included)."""
    recent: list[str] = []
    for line in out.splitlines():
        m = ERROR_LINE.match(line)
        if m is None:
            if line.strip():
                recent.append(line.strip())
            continue
        fr.errors += 1
        cause = _cause(line, _context(recent))
        nb = re.search(r"no virtual board for '([^']+)'", fr.note)
        if nb and "insmod for hm2_pci failed" in line:
            cause = f"board {nb.group(1)}: no virtual board (hm2_pci finds no card)"
        if cause not in fr.causes:
            fr.causes.append(cause)
        if fr.status != "failed":
            fr.status = "failed"
            where = m.group("file")
            if where.startswith(f"{HALLIB}/"):
                where = "LIB:" + where[len(str(HALLIB)) + 1 :]
            if fr.name.endswith(".tcl") and where != fr.name:
                where = f"{fr.name} → {where}"
            fr.first_error = f"{where}:{m.group('line')}: {m.group('msg')}"
            fr.context = _context(recent)
        recent = []


def _twopass(steps: list[Step], work: Path, ini: halprep.Ini) -> Path:
    """TWOPASS=on: all loadrt lines of the .hal files first, merged per
    module, as LinuxCNC does; returns the file with the merged lines."""
    lines: list[list[str]] = []
    for step in steps:
        if step.kind == "tcl" or step.dst is None:
            continue
        out = []
        for text in step.dst.read_text().split("\n"):
            body = text.split("#", 1)[0].split()
            if body and body[0] == "loadrt" and len(body) > 1:
                lines.append(halprep.resolve(" ".join(body), ini).split())
                out.append(f"#compat: twopass: {text.strip()}")
            else:
                out.append(text)
        step.dst.write_text("\n".join(out))
    merged = work / "compat-twopass.hal"
    merged.write_text("\n".join(halprep.twopass_merge(lines)) + "\n")
    return merged


def _run_tcl(
    sess: session.Session,
    step: Step,
    ini: halprep.Ini,
    ctx: halprep.Context,
    hw: Hardware,
    twopass: bool,
) -> None:
    """A .tcl HALFILE: haltcl runs it with the rule applied to every HAL
    command it makes (tclfilter); the motion stand-in is loaded by haltcl
    before motmod's command when that is the first."""
    assert step.src is not None
    server = tclfilter.Server(ini, ctx, hw.hook, lambda: _standin_lines(ctx))
    try:
        wrapper = sess.work / f"compat-tcl-{step.src.stem}.tcl"
        # the configuration's own file runs from its copy (error lines name
        # it as the INI does); a LIB: file from LinuxCNC's HAL library
        script = step.src
        if step.dst is not None and step.dst.exists():
            script = step.dst.relative_to(sess.work)
        wrapper.write_text(tclfilter.wrapper(server.port, script, step.args, twopass))
        rc, out = sess.run(
            [str(sess.bindir / "haltcl"), "-i", "compat.ini", wrapper.name], server.serve
        )
    finally:
        server.close()
    fr = step.fr
    for _, a in server.actions:
        if a.kind in ("remove", "rewrite"):
            counts = fr.removed if a.kind == "remove" else fr.rewritten
            counts[a.part] = counts.get(a.part, 0) + 1
    notes = [a.why for _, a in server.actions if a.kind == "keep" and a.why]
    fr.note = "; ".join(dict.fromkeys(notes))
    _parse_output(out, fr)
    if rc != 0 and fr.status != "failed":
        recent = [ln.strip() for ln in out.splitlines() if ln.strip()]
        fr.status, fr.errors = "failed", 1
        fr.first_error = f"{fr.name}: haltcl exited with status {rc}"
        fr.context = _context(recent)
        fr.causes.append(f"haltcl: exit status {rc} ({' / '.join(recent[-2:])})")


def _run_steps(
    sess: session.Session,
    steps: list[Step],
    ini: halprep.Ini,
    ctx: halprep.Context,
    hw: Hardware,
    res: ConfigResult,
) -> None:
    twopass = (ini.get("HAL", "TWOPASS") or "").lower() not in ("", "0", "off", "no", "false")
    if twopass:
        for step in steps:
            if step.kind != "tcl":
                _prepare(step, ini, ctx, hw, sess.work)
        merged = _twopass(steps, sess.work, ini)
        fr = FileResult("TWOPASS loadrt lines")
        res.files.insert(0, fr)
        steps.insert(0, Step(fr, "hal", None, merged, prepared=True))
    for step in steps:
        if step.kind == "tcl":
            _run_tcl(sess, step, ini, ctx, hw, twopass)
            continue
        rel = (
            str(step.dst.relative_to(sess.work))
            if step.prepared and step.dst
            else (_prepare(step, ini, ctx, hw, sess.work))
        )
        res.hardware = hw.used
        _load_standin(sess, ctx, res)
        _, out = sess.halcmd("-k", "-i", "compat.ini", "-f", rel)
        _parse_output(out, step.fr)
    res.hardware = hw.used


def standin_rtlib(bindir: Path) -> Path:
    """The motion stand-in's modules (tests/compat/standin), built with our
    halcompile into the build's compat/standin folder when missing or older
    than their .comp files; returns that folder (for HAL_RTLIB_PATH)."""
    out = bindir.parent / "compat" / "standin"
    out.mkdir(parents=True, exist_ok=True)
    for comp in sorted((HERE / "standin").glob("*.comp")):
        so = out / (comp.stem + ".so")
        if so.exists() and so.stat().st_mtime >= comp.stat().st_mtime:
            continue
        # built aside and renamed into place: concurrent runs (the tests)
        # never load a half-written module
        with tempfile.TemporaryDirectory(dir=out) as tmp:
            r = subprocess.run(
                [str(bindir / "halcompile"), "-c", str(comp)],
                cwd=tmp,
                capture_output=True,
                text=True,
            )
            built = Path(tmp) / so.name
            if r.returncode != 0 or not built.exists():
                why = (r.stderr or r.stdout)[-300:]
                raise RuntimeError(f"halcompile -c {comp.name} failed: {why}")
            os.replace(built, so)
    return out


def _standin_lines(ctx: halprep.Context) -> list[str]:
    """The HAL lines that load the motion stand-in, once, after the rule has
    met a motmod line (ctx.standin_joints); none otherwise."""
    if not ctx.standin_joints or ctx.standin_loaded:
        return []
    ctx.standin_loaded = True
    return halprep.standin_lines(ctx.standin_joints)


def _load_standin(sess: session.Session, ctx: halprep.Context, res: ConfigResult) -> None:
    """Before a prepared .hal file runs: loads the motion stand-in when the
    file (or an earlier one) has a motmod line; a failure is the run's error."""
    lines = _standin_lines(ctx)
    if not lines:
        return
    path = sess.work / "compat-motion-standin.hal"
    path.write_text("\n".join(lines) + "\n")
    rc, out = sess.halcmd("-k", "-f", path.name)
    res.run_error = res.run_error or _run_error(rc, out, "motion stand-in")


def _run_error(rc: int, out: str, what: str) -> str:
    errors = [ln for ln in out.splitlines() if ERROR_LINE.match(ln)]
    if rc == 0 and not errors:
        return ""
    return f"{what}: " + (errors[0] if errors else f"exit status {rc}: {out[-300:]}")


def run_config(
    ini_path: Path, samples: Path, bindir: Path, timeout: float, keep: Path | None = None
) -> ConfigResult:
    res = ConfigResult(str(ini_path.relative_to(samples)))
    t0 = time.monotonic()
    tmp = Path(tempfile.mkdtemp(prefix="cp"))
    hw = Hardware(tmp)
    sess = None
    try:
        work = tmp / "cfg"
        _copy_config(ini_path, work)
        text = halprep.expand_includes(
            ini_path.read_text(errors="replace"),
            lambda p: (ini_path.parent / p).read_text(errors="replace"),
        )
        (work / "compat.ini").write_text(text)
        ini = halprep.parse_ini(text)
        res.postgui = ini.all("HAL", "POSTGUI_HALFILE")
        steps = _plan(res, ini, ini_path.parent, work)
        ctx = _context_for(ini_path.parent)
        sess = session.Session(bindir, work, "compat.ini", t0 + timeout)
        sess.env["HAL_RTLIB_PATH"] = ":".join(
            p for p in (str(standin_rtlib(bindir)), os.environ.get("HAL_RTLIB_PATH", "")) if p
        )
        _run_steps(sess, steps, ini, ctx, hw, res)
        rc, out = sess.halcmd("simrun", RUN_NS)
        res.run_error = res.run_error or _run_error(rc, out, f"simrun {RUN_NS}")
    except session.Timeout:
        res.run_error = f"no result within {timeout:.0f} s"
    except Exception as e:  # a broken configuration is a result, not a crash
        res.run_error = res.run_error or f"preparation failed: {e}"
    finally:
        if sess is not None:
            out = sess.end()
            if "Sanitizer" in sess.log_path.read_text(errors="replace"):
                res.run_error = res.run_error or f"a sanitizer reported an error: {out[-300:]}"
        hw.stop()
        if keep is not None and (tmp / "cfg").exists():
            dest = keep / res.ini
            shutil.rmtree(dest, ignore_errors=True)
            shutil.copytree(tmp / "cfg", dest, symlinks=True)
        shutil.rmtree(tmp, ignore_errors=True)
        res.seconds = time.monotonic() - t0
    return res


# ---- discovery, report, main ------------------------------------------------


def find_inis(samples: Path, sets: list[str]) -> list[Path]:
    out: list[Path] = []
    for s in sets:
        for d in sorted(samples.glob(s)):
            out += sorted(d.rglob("*.ini")) if d.is_dir() else []
    keep = []
    for p in out:
        ini = halprep.parse_ini(p.read_text(errors="replace"))
        if any(v.split() for v in ini.all("HAL", "HALFILE") + ini.all("HAL", "HALCMD")):
            keep.append(p)
    return keep


def ensure_linuxcnc(samples: Path) -> None:
    if samples.exists():
        return
    print("compat: LinuxCNC's sample configurations are missing; installing linuxcnc-uspace")
    cmd = ["apt-get", "install", "-y", "linuxcnc-uspace"]
    if os.geteuid() != 0:
        cmd = ["sudo", "-n", *cmd]
    r = subprocess.run(cmd)
    if r.returncode != 0 or not samples.exists():
        print(
            f"compat: cannot install linuxcnc-uspace (exit {r.returncode}); {samples} missing",
            file=sys.stderr,
        )
        sys.exit(2)


def _md(s: str) -> str:
    return s.replace("|", "\\|").replace("\n", " ")


def report(results: list[ConfigResult]) -> str:
    absent = [f for r in results for f in r.files if f.status == "absent"]
    files = [f for r in results for f in r.files if f.status != "absent"]
    ok_files = sum(f.status == "loaded" for f in files)
    lines = [
        "# make compat: LinuxCNC 2.9 sample configurations on this HAL",
        "",
        f"{sum(r.ok for r in results)} of {len(results)} configurations and {ok_files} of"
        f" {len(files)} HAL files loaded and ran {RUN_NS} (rule: docs/compat.md);"
        f" {len(absent)} HAL files named by an INI are not in LinuxCNC's package.",
        "",
        "| configuration | HAL file | result | removed | rewritten |",
        "|---|---|---|---|---|",
    ]
    for r in results:
        for f in r.files:
            if f.status == "loaded":
                result = "loaded"
            else:
                result = f"**{f.status}** at {_md(f.first_error)}"
                if f.context:
                    result += f" ({_md(f.context)})"
                if f.errors > 1:
                    result += f" (+{f.errors - 1} more failing lines)"
            if f.note:
                result += f"; {_md(f.note)}"
            rem = ", ".join(f"{k} {v}" for k, v in sorted(f.removed.items()))
            rew = ", ".join(f"{k} {v}" for k, v in sorted(f.rewritten.items()))
            lines.append(f"| {r.ini} | {f.name} | {result} | {rem} | {rew} |")
        if r.run_error:
            lines.append(f"| {r.ini} | (run) | **failed**: {_md(r.run_error)} | | |")
        if not r.files:
            lines.append(f"| {r.ini} | (none) | no HALFILE | | |")
    lines += ["", "## Failures by first message", ""]
    causes: dict[str, int] = {}
    for f in files:
        if f.status not in ("loaded", "absent"):
            key = re.sub(r"^\S+:\d+: ", "", f.first_error)
            key = f"{key} ({f.context})" if f.context else key
            key = re.sub(r"/tmp/cp[^/\s]+/", "<tmp>/", key)
            causes[key] = causes.get(key, 0) + 1
    for k, n in sorted(causes.items(), key=lambda kv: -kv[1]):
        lines.append(f"- {n} × {_md(k)}")
    lines += ["", "## Everything that failed, by cause (files with at least one such line)", ""]
    every: dict[str, set[str]] = {}
    for r in results:
        for f in r.files:
            for c in f.causes or ([f.first_error] if f.status == "failed" else []):
                every.setdefault(c, set()).add(f"{r.ini}:{f.name}")
    for c, where in sorted(every.items(), key=lambda kv: (-len(kv[1]), kv[0])):
        lines.append(f"- {len(where)} × {_md(c)}")
    boards: dict[str, int] = {}
    for f in [f for r in results for f in r.files]:
        for m in re.finditer(r"no virtual board for '([^']+)'", f.note):
            boards[m.group(1)] = boards.get(m.group(1), 0) + 1
    if boards:
        lines += [
            "",
            "Boards without a virtual board (their driver line runs as written): "
            + ", ".join(f"{b} ({n} files)" for b, n in sorted(boards.items()))
            + ".",
        ]
    post = sorted({p for r in results for p in r.postgui})
    if post:
        lines += ["", f"Not run (loaded by the GUI after it starts): {', '.join(post)}."]
    return "\n".join(lines) + "\n"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--samples", type=Path, default=SAMPLES)
    ap.add_argument("--set", action="append", help="glob under sample-configs (repeatable)")
    ap.add_argument("--only", help="run only INI files whose path contains this text")
    ap.add_argument("--out", type=Path, default=build_dir() / "compat")
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument(
        "--keep", type=Path, help="keep each prepared configuration under this directory"
    )
    args = ap.parse_args()
    ensure_linuxcnc(args.samples)
    bindir = build_dir() / "bin"
    for prog in ("halcmd", "haltcl", "halrun"):
        if not (bindir / prog).exists():
            print(f"compat: {bindir / prog} is not built (run make)", file=sys.stderr)
            return 2
    inis = find_inis(args.samples, args.set or DEFAULT_SETS)
    if args.only:
        inis = [p for p in inis if args.only in str(p)]
    results = []
    for i, ini in enumerate(inis, 1):
        r = run_config(ini, args.samples, bindir, args.timeout, args.keep)
        results.append(r)
        state = "ok" if r.ok else "FAILED"
        print(f"[{i}/{len(inis)}] {r.ini}: {state} ({r.seconds:.1f} s)", flush=True)
    text = report(results)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "report.md").write_text(text)
    (args.out / "report.json").write_text(json.dumps([asdict(r) for r in results], indent=1))
    print(text)
    print(f"compat: report in {args.out / 'report.md'}")
    return 0 if all(r.ok for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
