# SPDX-License-Identifier: GPL-2.0-or-later
"""Shared helpers of the halview tests: HAL sessions and a siggen model."""

from __future__ import annotations

import csv
import math
import os
import re
import subprocess
import textwrap
import uuid
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BUILD = Path(os.environ.get("HM_BUILD", ROOT / "build"))
BIN = BUILD / "bin"
HALRUN = BIN / "halrun"
TOOLS = [BIN / t for t in ("halmeter", "halscope", "halshow", "halweb")]
BUILT = [HALRUN, BUILD / "lib" / "libhalview.so", BUILD / "lib" / "rtlib" / "scope_rt.so", *TOOLS]


def env(instance: str | None = None) -> dict[str, str]:
    e = dict(os.environ)
    e["HAL_INSTANCE"] = instance or "hv-" + uuid.uuid4().hex[:10]
    e["PATH"] = f"{BIN}:{e.get('PATH', '')}"
    e.pop("HAL_SIMCLOCK", None)
    return e


def halrun(
    tmp: Path, hal: str, sim: bool = True, timeout: float = 120, instance: str | None = None
) -> subprocess.CompletedProcess[str]:
    """Run a HAL file with halrun (-S: simulated clock) in its own session."""
    (tmp / "test.hal").write_text(textwrap.dedent(hal))
    args = [str(HALRUN)] + (["-S"] if sim else []) + ["-f", "test.hal"]
    return subprocess.run(
        args, cwd=tmp, env=env(instance), text=True, capture_output=True, timeout=timeout
    )


def read_csv(path: Path) -> tuple[list[str], list[list[str]]]:
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def parse_vcd(text: str) -> dict[str, list[tuple[int, str]]]:
    """Hierarchical name (below the top scope) -> [(time, value)] from VCD
    text; "#end" -> [(last time stamp, "")]."""
    names: dict[str, str] = {}
    scope: list[str] = []
    body = text.split("$enddefinitions")
    for m in re.finditer(r"\$(scope \w+ (\S+)|upscope|var \w+ \d+ (\S+) (\S+)) ", body[0]):
        if m.group(2):
            scope.append(m.group(2))
        elif m.group(1) == "upscope":
            scope.pop()
        else:
            names[m.group(3)] = ".".join(scope[1:] + [m.group(4)])
    changes: dict[str, list[tuple[int, str]]] = {n: [] for n in names.values()}
    t = -1
    for line in body[1].splitlines():
        line = line.strip()
        if line.startswith("#"):
            t = int(line[1:])
        elif line[:1] in ("b", "r"):
            value, ident = line[1:].split()
            changes[names[ident]].append((t, line[0] + value))
        elif line[:1] in ("0", "1"):
            changes[names[line[1:]]].append((t, line[0]))
    changes["#end"] = [(t, "")]
    return changes


TWO_PI = 6.2831854  # siggen's constant (host/hal/components/siggen.comp)


class Siggen:
    """One siggen channel, step by step as siggen.comp computes it."""

    def __init__(self, freq: float, amp: float = 1.0, offset: float = 0.0) -> None:
        self.freq, self.amp, self.offset = freq, amp, offset
        self.phase = 0.0

    def update(self, period_ns: int) -> dict[str, float]:
        fperiod = period_ns * 1e-9
        step = self.freq * fperiod
        if step > 0.5:
            step = 0.5
        self.phase += step
        if self.phase >= 1.0:
            self.phase -= 1.0
        ph, a, o = self.phase, self.amp, self.offset
        return {
            "sawtooth": (ph * 2.0 - 1.0) * a + o,
            "triangle": ((1.0 - ph * 4.0) if ph <= 0.5 else (ph * 4.0 - 3.0)) * a + o,
            "square": (a + o) if ph > 0.5 else (-a + o),
            "clock": 1.0 if ph > 0.5 else 0.0,
            "sine": math.sin(ph * TWO_PI) * a + o,
            "cosine": math.cos(ph * TWO_PI) * a + o,
        }


class LiveHal:
    """A HAL session on the wall clock left running by `halcmd -f` (threads
    started), with tools started in it; stop() ends everything (halrun -U)."""

    def __init__(self, tmp: Path, hal: str) -> None:
        self.env = env()
        self.tmp = tmp
        self.procs: list[subprocess.Popen[str]] = []
        (tmp / "live.hal").write_text(textwrap.dedent(hal))
        r = subprocess.run(
            [str(BIN / "halcmd"), "-f", "live.hal"],
            cwd=tmp,
            env=self.env,
            text=True,
            capture_output=True,
            timeout=60,
        )
        if r.returncode != 0:
            self.stop()
            raise AssertionError(f"live.hal failed: {r.stderr}")

    def halcmd(self, *args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [str(BIN / "halcmd"), *args], env=self.env, text=True, capture_output=True, timeout=60
        )

    def getp(self, name: str) -> str:
        r = self.halcmd("getp", name)
        assert r.returncode == 0, r.stderr
        return r.stdout.strip()

    def run(self, *args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [str(a) for a in args], env=self.env, text=True, capture_output=True, timeout=timeout
        )

    def start(self, *args: str) -> subprocess.Popen[str]:
        p = subprocess.Popen(
            [str(a) for a in args],
            env=self.env,
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        self.procs.append(p)
        return p

    def start_web(self, *args: str) -> tuple[subprocess.Popen[str], str]:
        """A halweb-style server on a free port; returns it and its URL."""
        p = self.start(*args, "--port", "0")
        assert p.stdout is not None
        line = p.stdout.readline()
        if not line.startswith("halweb: http://"):
            p.kill()
            raise AssertionError(
                f"no URL from {args}: {line!r} {p.stderr.read() if p.stderr else ''}"
            )
        return p, line.split()[1]

    def stop(self) -> None:
        for p in self.procs:
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        subprocess.run([str(HALRUN), "-U"], env=self.env, capture_output=True, timeout=60)
