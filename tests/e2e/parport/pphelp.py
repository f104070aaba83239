# SPDX-License-Identifier: GPL-2.0-or-later
"""Helpers of the hal_parport tests: virtual parallel ports (bin/vparport)
and halrun sessions on the simulated clock.

Pin stimulus and measurements that must happen while HAL is loaded run
inside the HAL script as ``loadusr -w vparport ...`` (threads only run
inside ``simrun``, so the port is seen at an exact simulated time); their
output is collected between ``@@tag`` markers by :func:`values`.

The pin tables below are the reference, written from the seed's "Parport"
chapter and LinuxCNC 2.9's hal_parport(1), not from the driver.
"""

from __future__ import annotations

import os
import subprocess
import uuid
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
BUILD = Path(os.environ.get("HM_BUILD", str(ROOT / "build")))
HALRUN = BUILD / "bin" / "halrun"
VPARPORT = BUILD / "bin" / "vparport"
RTLIB = BUILD / "lib" / "rtlib"

DATA = list(range(2, 10))
STATUS = [10, 11, 12, 13, 15]
CONTROL = [1, 14, 16, 17]
OUT_PINS = {
    "out": sorted(DATA + CONTROL),
    "epp": sorted(DATA + CONTROL),
    "in": CONTROL,
    "x": DATA,
}
IN_PINS = {
    "out": STATUS,
    "epp": STATUS,
    "in": sorted(DATA + STATUS),
    "x": sorted(CONTROL + STATUS),
}


def require_built() -> None:
    """A missing part is a failure, never a skip."""
    for p in (HALRUN, VPARPORT, RTLIB / "hal_parport.so", RTLIB / "probe_parport.so"):
        assert p.exists(), f"{p} is not built (run make)"


def vparport(*args: object, check: bool = True) -> subprocess.CompletedProcess[str]:
    r = subprocess.run(
        [str(VPARPORT), *(str(a) for a in args)], capture_output=True, text=True, timeout=30
    )
    if check:
        assert r.returncode == 0, f"vparport {args}: {r.stderr}"
    return r


def create(tmp: Path, name: str = "pp", *opts: str) -> Path:
    """A virtual port as a file in tmp (its path is the sim: name)."""
    path = tmp / name
    vparport("create", path, *opts)
    return path


def levels(text: str) -> dict[int, int]:
    """'2=1 3=0 ...' -> {2: 1, 3: 0}."""
    out: dict[int, int] = {}
    for word in text.split():
        pin, _, lv = word.partition("=")
        out[int(pin)] = int(lv)
    return out


def get(port: Path, *pins: int) -> dict[int, int]:
    return levels(vparport("get", port, *pins).stdout)


def counters(port: Path) -> dict[str, tuple[int, int]]:
    out: dict[str, tuple[int, int]] = {}
    for line in vparport("counters", port).stdout.splitlines():
        w = line.split()
        if w[0] == "contention":
            out["contention"] = (int(w[1]), 0)
        else:
            out[w[0]] = (int(w[2]), int(w[4]))
    return out


def log(port: Path, *pins: int) -> list[tuple[int, dict[int, int]]]:
    """The port's output changes: (time, levels) with the register writes of
    one instant merged (a write of data then control is one change)."""
    args: list[object] = ["log", port]
    for p in pins:
        args += ["--pin", p]
    out: list[tuple[int, dict[int, int]]] = []
    for line in vparport(*args).stdout.splitlines():
        t, _, rest = line.partition(" ")
        if out and out[-1][0] == int(t):
            out.pop()
        if not out or out[-1][1] != levels(rest):
            out.append((int(t), levels(rest)))
    return out


def owner(port: Path) -> int:
    for line in vparport("show", port).stdout.splitlines():
        if line.startswith("owner"):
            return int(line.split()[1])
    raise AssertionError("no owner line")


def register(port: Path, name: str) -> int:
    for line in vparport("show", port).stdout.splitlines():
        if line.startswith(name + " "):
            return int(line.split()[1], 16)
    raise AssertionError(f"no {name} line")


# ---- HAL scripts ------------------------------------------------------------


def tag(name: str, *hal_names: str) -> str:
    """Script lines printing '@@name' then getp of each object."""
    return f"loadusr -w echo @@{name}\n" + "".join(f"getp {h}\n" for h in hal_names)


def probe(name: str, port: Path, *pins: int) -> str:
    """Script lines printing '@@name' then the port's pin levels."""
    return (
        f"loadusr -w echo @@{name}\nloadusr -w {VPARPORT} get {port} {' '.join(map(str, pins))}\n"
    )


def drive(port: Path, levels_: dict[int, int | str]) -> str:
    words = " ".join(f"{p}={v}" for p, v in levels_.items())
    return f"loadusr -w {VPARPORT} drive {port} {words}\n"


def halrun(
    tmp: Path, script: str, timeout: float = 120, args: tuple[str, ...] = ("-S",)
) -> subprocess.CompletedProcess[str]:
    f = tmp / f"t{uuid.uuid4().hex[:6]}.hal"
    f.write_text(script)
    env = dict(os.environ)
    env["HAL_INSTANCE"] = "pp-" + uuid.uuid4().hex[:10]
    env["HM_BUILD"] = str(BUILD)
    env["PATH"] = f"{BUILD / 'bin'}:{env.get('PATH', '')}"
    r = subprocess.run(
        [str(HALRUN), *args, "-f", str(f)],
        capture_output=True,
        text=True,
        timeout=timeout,
        env=env,
        cwd=tmp,
    )
    out = r.stdout + r.stderr
    for bad in ("AddressSanitizer", "LeakSanitizer", "runtime error:"):
        assert bad not in out, f"sanitizer report in the HAL session:\n{out}"
    return r


def values(out: str) -> dict[str, list[str]]:
    """'@@name' markers and the non-empty lines after them."""
    res: dict[str, list[str]] = {}
    cur: str | None = None
    for line in out.splitlines():
        if line.startswith("@@"):
            cur = line[2:].strip()
            res[cur] = []
        elif cur is not None and line.strip() and not line.startswith("hal_parport:"):
            res[cur].append(line.strip())
    return res


def bit(s: str) -> int:
    assert s in ("TRUE", "FALSE"), s
    return 1 if s == "TRUE" else 0


def section(out: str, title: str) -> str:
    """The block of `show` output that starts with title (up to a blank line)."""
    lines = out.splitlines()
    for i, line in enumerate(lines):
        if line.startswith(title):
            block = []
            for ln in lines[i:]:
                if not ln.strip():
                    break
                block.append(ln)
            return "\n".join(block) + "\n"
    return ""
