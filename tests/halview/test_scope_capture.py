# SPDX-License-Identifier: GPL-2.0-or-later
"""halscope + scope_rt captures under the simulated clock, checked sample by
sample against a model of siggen (tests/halview/hvutil.py) and of the
trigger rule (docs/halscope.md)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from hvutil import BUILT, Siggen, halrun, read_csv

pytestmark = pytest.mark.requires_build(*BUILT)

PERIOD = 100_000  # ns
FREQ = 100.0  # Hz: 100 samples per period of the wave


def model_records(n: int, freq: float = FREQ, period: int = PERIOD) -> list[dict[str, float]]:
    """Record r = siggen's outputs after its (r+1)-th update: scope.sample is
    added after siggen.0.update and samples from the first period on."""
    g = Siggen(freq)
    return [g.update(period) for _ in range(n)]


def expected_trigger(recs: list[dict[str, float]], pretrig: int, level: float) -> int:
    for r in range(max(1, pretrig), len(recs)):
        if recs[r - 1]["square"] < level <= recs[r]["square"]:
            return r
    raise AssertionError("the model never triggers")


HAL_SQUARE = """\
loadrt threads name1=fast period1={period}
loadrt siggen
addf siggen.0.update fast
setp siggen.0.frequency {freq}
net sq siggen.0.square
setp fast.tmax 7
loadrt scope_rt
addf scope.sample fast
loadusr -Wn halscope halscope --channels siggen.0.square,sig:sq,siggen.0.clock,siggen.0.sawtooth,param:fast.tmax --trigger siggen.0.square --level 0 --edge rising --samples 400 --position 25 --out cap.csv --out cap.vcd
simrun 100ms
waitusr halscope
"""


def test_square_wave_triggered(tmp_path: Path) -> None:
    r = halrun(tmp_path, HAL_SQUARE.format(period=PERIOD, freq=FREQ))
    assert r.returncode == 0, r.stderr
    head, rows = read_csv(tmp_path / "cap.csv")
    assert head == [
        "index",
        "time",
        "siggen.0.square",
        "sq",
        "siggen.0.clock",
        "siggen.0.sawtooth",
        "fast.tmax",
    ]
    assert len(rows) == 400
    idx = [int(r[0]) for r in rows]
    assert idx == list(range(-100, 300)), "25 % of 400 samples before the trigger"
    assert [r[1] for r in rows[:2]] == ["-0.010000000", "-0.009900000"]
    # the whole record against the model, value for value
    recs = model_records(2000)
    trig = expected_trigger(recs, 100, 0.0)
    for row in rows:
        m = recs[trig + int(row[0])]
        assert float(row[2]) == m["square"] and float(row[3]) == m["square"]
        assert int(row[4]) == int(m["clock"])
        assert float(row[5]) == m["sawtooth"]
        assert row[6] == "7"
    sq = [float(r[2]) for r in rows]
    assert sq[99] == -1.0 and sq[100] == 1.0, "the trigger row is the first high sample"
    rises = [i - 100 for i in range(1, 400) if sq[i - 1] < 0 <= sq[i]]
    falls = [i - 100 for i in range(1, 400) if sq[i - 1] > 0 >= sq[i]]
    # 100 Hz at 100 us: a period of exactly 100 samples, high for 50
    assert rises == [0, 100, 200]
    assert [f - r for f, r in zip(falls[1:], rises)] == [50, 50, 50]
    # the VCD holds the same changes at the session's (simulated) times
    vcd = (tmp_path / "cap.vcd").read_text()
    ident = re.search(r"\$var real 64 (\S+) square \$end", vcd)
    assert ident
    t_trig = (trig + 1) * PERIOD  # record r is taken at the end of period r+1
    times = [int(t) for t in re.findall(r"^#(\d+)$", vcd, re.M)]
    assert times[0] == t_trig - 100 * PERIOD
    changes = re.findall(r"^#(\d+)\n(?:.*\n)*?r(\S+) " + re.escape(ident.group(1)) + "$", vcd, re.M)
    assert changes  # at least the initial value
    assert f"#{t_trig}\n" in vcd


HAL_MODES = """\
loadrt threads name1=fast period1=100000
loadrt siggen
addf siggen.0.update fast
setp siggen.0.frequency 100
loadrt scope_rt
addf scope.sample fast
loadusr -Wn halscope halscope -c siggen.0.clock,siggen.0.square --trigger siggen.0.clock --edge falling --level 0.5 --samples 100 --position 10 --mode {mode} --out cap.csv {extra}
simrun 100ms
waitusr halscope
"""


def test_falling_edge_on_bit(tmp_path: Path) -> None:
    r = halrun(tmp_path, HAL_MODES.format(mode="single", extra=""))
    assert r.returncode == 0, r.stderr
    _, rows = read_csv(tmp_path / "cap.csv")
    clock = [int(r[1 + 1]) for r in rows]
    assert len(rows) == 100 and int(rows[0][0]) == -10
    assert clock[9] == 1 and clock[10] == 0


def test_auto_mode_forces_a_trigger(tmp_path: Path) -> None:
    """A level the bit never crosses: auto captures anyway, one record
    length after the pre-trigger samples are in."""
    hal = HAL_MODES.format(mode="auto", extra="").replace("--level 0.5", "--level 5")
    r = halrun(tmp_path, hal)
    assert r.returncode == 0, r.stderr
    _, rows = read_csv(tmp_path / "cap.csv")
    assert len(rows) == 100
    # records 0..: pretrig 10, forced when record 10 + 100 - 1 = 109 is in
    recs = model_records(200)
    first = 109 - 10
    assert [int(r[2]) for r in rows] == [int(recs[first + i]["clock"]) for i in range(100)]


def test_normal_mode_count_and_mult(tmp_path: Path) -> None:
    """Two captures re-armed one after the other, sampling every 2nd period."""
    hal = HAL_MODES.format(mode="normal", extra="--count 2 --mult 2")
    r = halrun(tmp_path, hal)
    assert r.returncode == 0, r.stderr
    for n in (1, 2):
        head, rows = read_csv(tmp_path / f"cap-{n}.csv")
        assert len(rows) == 100
        assert rows[1][1] == "-0.001800000", "time steps of 2 periods"
        clock = [int(r[2]) for r in rows]
        assert clock[9] == 1 and clock[10] == 0


HAL_ROLL16 = """\
loadrt threads name1=base period1=25000
loadrt siggen num_chan=3
addf siggen.0.update base
addf siggen.1.update base
addf siggen.2.update base
setp siggen.0.frequency 1000
setp siggen.1.frequency 330
setp siggen.2.frequency 77
loadrt scope_rt
addf scope.sample base
loadusr -Wn halscope halscope -c {chans} --mode roll --duration 1s --out roll.csv
simrun 1s
waitusr halscope
"""
OUTS = ["sine", "cosine", "triangle", "sawtooth", "square", "clock"]


def test_sixteen_channels_one_second_roll(tmp_path: Path) -> None:
    """16 channels at a 25 us thread for 1 s of simulated time: 40000
    records, none lost, every value as siggen computed it."""
    names = [f"siggen.{c}.{o}" for c in range(3) for o in OUTS][:16]
    r = halrun(tmp_path, HAL_ROLL16.format(chans=",".join(names)), timeout=300)
    assert r.returncode == 0, r.stderr
    assert "40000 samples, 0 lost" in r.stderr
    head, rows = read_csv(tmp_path / "roll.csv")
    assert head[2:] == names
    assert len(rows) == 40000
    gens = [Siggen(f) for f in (1000.0, 330.0, 77.0)]
    for n, row in enumerate(rows):
        assert int(row[0]) == n
        outs = [g.update(25_000) for g in gens]
        for i, name in enumerate(names):
            c, o = int(name.split(".")[1]), name.split(".")[2]
            got = int(row[2 + i]) if o == "clock" else float(row[2 + i])
            assert got == outs[c][o], (n, name)


HAL_STEPGEN = """\
loadrt threads name1=base period1=25000 fp1=0 name2=servo period2=1000000
loadrt stepgen step_type=0 ctrl_type=v
addf stepgen.make-pulses base
addf stepgen.update-freq servo
addf stepgen.capture-position servo
setp stepgen.0.position-scale 1000
setp stepgen.0.steplen 1
setp stepgen.0.stepspace 1
setp stepgen.0.velocity-cmd 3.0
setp stepgen.0.enable 1
simrun 5ms
loadrt scope_rt
addf scope.sample base
loadusr -Wn halscope halscope -c stepgen.0.step,stepgen.0.rawcounts --samples 4000 --position 0 --out step.csv
simrun 101ms
waitusr halscope
"""


def test_stepgen_step_pin_at_25us(tmp_path: Path) -> None:
    """Every step of a 3 kHz software stepgen at a 25 us base thread is
    resolved: one sample high (steplen 1 period), as many rising edges as
    the position counter moved, one step every 333 1/3 us on average."""
    r = halrun(tmp_path, HAL_STEPGEN)
    assert r.returncode == 0, r.stderr
    _, rows = read_csv(tmp_path / "step.csv")
    assert len(rows) == 4000 and rows[1][1] == "0.000025000"
    step = [int(r[2]) for r in rows]
    raw = [int(r[3]) for r in rows]
    rises = [i for i in range(1, len(step)) if step[i - 1] == 0 and step[i] == 1]
    assert all(step[i + 1] == 0 for i in rises[:-1]), "each pulse is one period long"
    assert len(rises) == raw[-1] - raw[0] or len(rises) == raw[-1] - raw[0] - step[0]
    # each rising edge is the sample where rawcounts moves on
    assert all(raw[i] == raw[i - 1] + 1 for i in rises)
    gaps = [b - a for a, b in zip(rises, rises[1:])]
    assert set(gaps) <= {13, 14}, "333.3 us between steps = 13 or 14 periods of 25 us"
    assert abs(len(rises) - 100e-3 * 3000) <= 1


HAL_RELINK = """\
loadrt threads name1=fast period1=100000
loadrt siggen
loadrt mult2
addf siggen.0.update fast
setp siggen.0.frequency 100
net sa siggen.0.square mult2.0.in0
net sb siggen.0.sawtooth
loadusr -Wn halscope halscope --thread fast -c mult2.0.in0 --mode roll --duration 20ms -o r.csv
simrun 10ms
unlinkp mult2.0.in0
net sb mult2.0.in0
simrun 10ms
waitusr halscope
"""


def test_a_pin_is_followed_to_its_new_signal(tmp_path: Path) -> None:
    """Relinking a sampled pin while the scope runs: the samples follow it."""
    r = halrun(tmp_path, HAL_RELINK)
    assert r.returncode == 0, r.stderr
    _, rows = read_csv(tmp_path / "r.csv")
    recs = model_records(200)
    assert [float(r[2]) for r in rows] == [m["square"] for m in recs[:100]] + [
        m["sawtooth"] for m in recs[100:]
    ]
