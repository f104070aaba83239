# SPDX-License-Identifier: GPL-2.0-or-later
"""Shared parts of hm2machine and hm2tune: an example machine directory, a
virtual board with its machine, a HAL run on the simulated clock, the
sampled data and the plant's trace.

An example directory holds ``example.toml`` (what to run: board, machine
file, HAL file, the moves, the sampled columns per axis; see
examples/machines/README.md), the machine file and the HAL file.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
import uuid
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from vbplant import request

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def build_dir() -> Path:
    return Path(os.environ.get("HM_BUILD", str(ROOT / "build")))


def tool(name: str) -> str:
    p = build_dir() / "bin" / name
    if not p.exists():
        raise RuntimeError(f"{p} is missing: run `make build`")
    return str(p)


@dataclass
class Axis:
    name: str
    kind: str  # "servo" or "stepper"
    cmd: int  # sampler columns
    fb: int
    err: int | None = None  # pid.error: the following error as the loop sees it
    out: int | None = None
    unit: str = "mm"


@dataclass
class Example:
    path: Path
    name: str
    title: str
    board: str
    machine: Path
    hal: Path
    period_ns: int
    arm: list[str]
    axes: list[Axis]
    columns: int
    moves: dict[str, list[list[float]]]
    before: list[str] = field(default_factory=list)
    tune_open_loop: list[str] = field(default_factory=list)

    @staticmethod
    def load(path: Path) -> Example:
        f = path / "example.toml"
        try:
            d = tomllib.loads(f.read_text())
        except (OSError, tomllib.TOMLDecodeError) as exc:
            raise RuntimeError(f"{f}: {exc}") from exc
        try:
            axes = [
                Axis(
                    a["name"],
                    a["kind"],
                    a["cmd"],
                    a["fb"],
                    a.get("err"),
                    a.get("out"),
                    a.get("unit", "mm"),
                )
                for a in d["axis"]
            ]
            return Example(
                path=path,
                name=path.name,
                title=d["title"],
                board=d["board"],
                machine=path / d["machine"],
                hal=path / d["hal"],
                period_ns=int(d.get("period_ns", 1_000_000)),
                arm=list(d.get("arm", [])),
                axes=axes,
                columns=int(d["columns"]),
                moves={k: d[k]["moves"] for k in ("run", "short") if k in d},
                before=list(d.get("before", [])),
                tune_open_loop=list(d.get("tune_open_loop", [])),
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise RuntimeError(f"{f}: missing or bad key: {exc}") from exc


def expand_moves(moves: list[list[float]], period_ns: int) -> list[str]:
    """[[t1, t2, ..., hold_s], ...] -> one streamer line per servo period."""
    lines = []
    for m in moves:
        *targets, hold = m
        n = round(hold * 1e9 / period_ns)
        lines += [" ".join(f"{v:g}" for v in targets)] * n
    return lines


class Board:
    """A vboard process with a machine, on a private socket."""

    def __init__(self, board: str, machine: Path, workdir: Path, extra: list[str] = []) -> None:
        self.sock = str(Path(tempfile.mkdtemp(prefix="hm2m")) / "b.sock")
        self.log = workdir / "vboard.log"
        cmd = [tool("vboard"), "--socket", self.sock, "--board", board, "--machine", str(machine)]
        self.proc = subprocess.Popen(
            cmd + extra, stdout=self.log.open("w"), stderr=subprocess.STDOUT, cwd=workdir
        )
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            if "ready" in self.log.read_text():
                return
            if self.proc.poll() is not None:
                break
            time.sleep(0.05)
        text = self.log.read_text()
        self.stop()
        raise RuntimeError(f"vboard did not start: {text.strip()}")

    def plant(self, command: str) -> Any:
        status, text = request(self.sock, command)
        if status < 0:
            raise RuntimeError(f"vboard: {text}")
        return json.loads(text)

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(30)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        shutil.rmtree(Path(self.sock).parent, ignore_errors=True)

    def __enter__(self) -> Board:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()


def halrun(script: str, workdir: Path, env: dict[str, str], timeout: float = 3600) -> str:
    """Run a HAL script under halrun -S; its output (an error raises)."""
    f = workdir / "run.hal"
    f.write_text(script)
    e = dict(os.environ)
    e.update(env)
    e["HAL_INSTANCE"] = "hm2m-" + uuid.uuid4().hex[:10]
    r = subprocess.run(
        [tool("halrun"), "-S", "-f", str(f)],
        capture_output=True,
        text=True,
        cwd=workdir,
        env=e,
        timeout=timeout,
    )
    out = r.stdout + r.stderr
    (workdir / "halrun.log").write_text(out)
    if r.returncode != 0:
        raise RuntimeError(f"halrun failed ({r.returncode}); see {workdir / 'halrun.log'}:\n{out}")
    return out


def run_script(
    ex: Example,
    sock: str,
    moves: list[str],
    events: list[tuple[float, str]] = [],
    after: list[str] = [],
) -> tuple[str, int]:
    """The HAL lines of one recorded run: setup, arm, then `len(moves)`
    servo periods with the streamer, the sampler and the plant's trace on.
    events: (seconds into the recording, HAL line) - fault injection;
    after: lines once the recording is complete."""
    n = len(moves)
    # halstreamer -W must still be running when it is ready: the file must
    # not fit the streamer's FIFO (the examples use depth=64)
    if n <= 64:
        raise RuntimeError(f"{n} servo periods of moves: a run needs more than 64")
    s = f"source {ex.hal}\n"
    s += "".join(line + "\n" for line in ex.before)
    s += "simrun 20ms\n"
    s += "".join(line + "\n" for line in ex.arm)
    s += "simrun 20ms\n"
    s += f"loadusr -Wn hm2m-samp halsampler -N hm2m-samp -n {n} samples.txt\n"
    s += "loadusr -Wn hm2m-stream halstreamer -N hm2m-stream moves.txt\n"
    s += f"loadusr -w {tool('vbplant')} {sock} trace trace.csv\n"
    s += "setp streamer.0.enable 1\nsetp sampler.0.enable 1\n"
    done = 0
    for at, line in sorted(events):
        k = min(n, max(done, round(at * 1e9 / ex.period_ns)))
        if k > done:
            s += f"simrun {(k - done) * ex.period_ns}\n"
            done = k
        s += line + "\n"
    if n > done:
        s += f"simrun {(n - done) * ex.period_ns}\n"
    s += "setp sampler.0.enable 0\n"
    s += f"loadusr -w {tool('vbplant')} {sock} trace off\n"
    s += f"loadusr -w {tool('vbplant')} -o status.json {sock} status\n"
    # halsampler writes the last rows after the threads stopped: wait for them
    s += f"loadusr -w {sys.executable} {HERE / 'waitlines.py'} samples.txt {n}\n"
    s += "".join(line + "\n" for line in after)
    return s, n


def read_samples(path: Path, columns: int) -> list[list[float]]:
    rows = []
    for line in path.read_text().splitlines():
        if not line.strip() or line.startswith("overrun"):
            continue
        v = [float(x) for x in line.split()]
        if len(v) != columns:
            raise RuntimeError(f"{path}: a row has {len(v)} values, want {columns}")
        rows.append(v)
    return rows


def read_trace(path: Path) -> tuple[list[str], list[list[float]]]:
    lines = path.read_text().splitlines()
    head = lines[0].split(",")
    return head, [[float(x) for x in ln.split(",")] for ln in lines[1:]]
