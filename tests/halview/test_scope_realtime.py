# SPDX-License-Identifier: GPL-2.0-or-later
"""scope_rt on the wall clock (a real rtapi thread, not the simulated clock):
the reader is frozen (SIGSTOP) in the middle of a roll capture and the
thread does not wait for it; the samples it could not keep are counted as
lost, and every sample that arrives is whole.  Checked against a model of
siggen (tests/halview/hvutil.py): row N of the CSV must be siggen's outputs
after update K0 + N for one K0, for all 16 channels at once."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import time
from pathlib import Path
from typing import Iterator

import pytest

from hvutil import BIN, BUILT, LiveHal, Siggen, read_csv

pytestmark = pytest.mark.requires_build(*BUILT)

PERIOD = 100_000  # ns
FREQ = 7.0
LIVE = f"""\
loadrt threads name1=fast period1={PERIOD}
loadrt siggen num_chan=3
addf siggen.0.update fast
addf siggen.1.update fast
addf siggen.2.update fast
setp siggen.0.frequency {FREQ}
setp siggen.1.frequency {FREQ}
setp siggen.2.frequency {FREQ}
loadrt scope_rt
addf scope.sample fast
start
"""
OUTS = ["sine", "sawtooth", "square", "clock", "triangle"]
CHANNELS = [f"siggen.{g}.{o}" for g in range(3) for o in OUTS] + ["siggen.0.cosine"]


@pytest.fixture
def live(tmp_path: Path) -> Iterator[LiveHal]:
    hal = LiveHal(tmp_path, LIVE)
    yield hal
    hal.stop()


def wait_ready(live: LiveHal, name: str, proc: subprocess.Popen[str]) -> None:
    """The front end has armed the scope once its component is ready."""
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        assert proc.poll() is None, proc.stderr.read() if proc.stderr else ""
        comps = live.halcmd("show", "comp").stdout
        if re.search(rf"^\s*\d+\s+User\s+{name}\s+\d+\s+ready$", comps, re.M):
            return
        time.sleep(0.05)
    raise AssertionError(f"{name} never became ready")


def test_frozen_reader_does_not_stop_the_thread(live: LiveHal, tmp_path: Path) -> None:
    out = tmp_path / "roll.csv"
    records = 20_000  # 2 s of the 100 us thread
    p = live.start(
        BIN / "halscope",
        "-c",
        ",".join(CHANNELS),
        "--mode",
        "roll",
        "--duration",
        "2s",
        "--name",
        "hvscope",
        "--out",
        str(out),
    )
    wait_ready(live, "hvscope", p)
    time.sleep(0.3)
    os.kill(p.pid, signal.SIGSTOP)
    try:
        # the reader is frozen: the thread keeps running all the same
        before = live.getp("siggen.0.sawtooth")
        time.sleep(0.8)
        after = live.getp("siggen.0.sawtooth")
    finally:
        os.kill(p.pid, signal.SIGCONT)
    assert before != after, "the thread stood still while the reader was stopped"
    _, err = p.communicate(timeout=120)
    assert p.returncode == 0, err
    m = re.search(r"(\d+) samples, (\d+) lost", err)
    assert m, err
    got, lost = int(m.group(1)), int(m.group(2))
    # 0.8 s frozen = 8000 periods; the ring holds 16000 / 16 = 1000 records
    assert got + lost == records and lost > 0, err

    head, rows = read_csv(out)
    assert head[2:] == CHANNELS and len(rows) == got
    index = [int(r[0]) for r in rows]
    assert index[0] == 0 and index[-1] < records
    gaps = [b - a for a, b in zip(index, index[1:])]
    assert min(gaps) >= 1 and sum(g - 1 for g in gaps) + (records - 1 - index[-1]) == lost

    # every row is whole: the three generators agree channel for channel,
    # and row N is the model after update K0 + N (records are numbered by
    # the thread, so a gap of lost records is a gap of thread periods)
    for row in rows:
        vals = dict(zip(CHANNELS, row[2:]))
        for o in OUTS:
            assert vals[f"siggen.0.{o}"] == vals[f"siggen.1.{o}"] == vals[f"siggen.2.{o}"], row
    gen = Siggen(FREQ)
    first = [float(v) for v in rows[0][2:]]
    model: list[list[float]] = []
    k0 = None
    limit = 3_000_000  # 300 s of the thread: far more than the test takes
    while k0 is None:
        o = gen.update(PERIOD)
        model.append([o[c.split(".")[2]] for c in CHANNELS])
        if model[-1] == first:
            k0 = len(model) - 1
        assert len(model) < limit, "the first row is no state of siggen"
    need = k0 + index[-1] + 1
    while len(model) < need:
        o = gen.update(PERIOD)
        model.append([o[c.split(".")[2]] for c in CHANNELS])
    for n, row in zip(index, rows):
        assert [float(v) for v in row[2:]] == model[k0 + n], (n, row)
