# SPDX-License-Identifier: GPL-2.0-or-later
"""Encoder and StepGen features of the newer module versions through the real
driver (hostmot2 + hm2_sim) and the real Verilog, on SV2ST2_PRB (a 5i20
firmware of ours with QCount version 0x83 and StepGen version 0x42):

- probe-enable / probe-invert: the count is latched on the probe pin's
  active edge into count-latched / position-latched, and probe-enable drops
  back to 0 (hostmot2(9));
- index-mask / index-mask-invert: the index only counts while the
  IndexMask pin has the chosen level;
- counter-mode: A is a step (count on its rising edge), B the direction;
- quad-error / quad-error-enable: A and B changing together is reported
  while enabled, with the log line LinuxCNC prints, and cleared by
  re-enabling;
- input-a / input-b / input-index follow the filtered pin levels;
- the low-speed velocity from the count timestamps, and vel-timeout;
- swap_step_dir: Step leaves on the Direction pin and vice versa.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from hm2e2e import PFX, halrun, load, needs_vboard, num, probe, probed, tag, values, vboard

pytestmark = needs_vboard

CONFIG = "firmware=hm2/5i20/SV2ST2_PRB.BIT num_encoders=2 num_pwmgens=2 num_stepgens=2"
# SV2ST2_PRB.toml: encoder 0 on I/O 0..4, stepgen 0 on I/O 24 and 25
A, B, IDX, MASK, PRB = 0, 1, 2, 3, 4
SG_STEP, SG_DIR = 24, 25
ENC = f"{PFX}.encoder.00"


@pytest.fixture
def board(tmp_path: Path) -> Iterator[Path]:
    with vboard.VBoardProcess(tmp_path / "b.sock", "5i20", "SV2ST2_PRB") as vb:
        yield Path(vb.socket_path)
        assert vb.proc.poll() is None


def run_ok(tmp: Path, script: str) -> str:
    r = halrun(tmp, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert "failed" not in out, out
    return out


def drive(sock: Path, pins: str, level: str) -> str:
    return probe(sock, "drive", pins, level)


@pytest.mark.parametrize("invert", [1, 0])
def test_probe_latch(tmp_path: Path, board: Path, invert: int) -> None:
    """The active edge is rising with probe-invert = 1, falling with 0; the
    other edge, and any edge while probe-enable is 0, latch nothing."""
    idle, active = ("low", "high") if invert else ("high", "low")
    s = load(board, CONFIG) + f"setp {ENC}.scale 4\nsetp {ENC}.probe-invert {invert}\n"
    s += drive(board, str(PRB), idle)
    s += probe(board, "quad", A, B, 20000)
    s += "simrun 3ms\n"
    # an edge while not armed: ignored
    s += drive(board, str(PRB), active) + "simrun 1ms\n" + drive(board, str(PRB), idle)
    s += "simrun 1ms\n"
    s += f"setp {ENC}.probe-enable 1\n"
    s += "simrun 2ms\n"
    s += tag("armed", f"{ENC}.probe-enable", f"{ENC}.count", f"{ENC}.count-latched")
    s += drive(board, str(PRB), active)
    s += "simrun 2ms\n"
    s += tag("after", f"{ENC}.probe-enable", f"{ENC}.count-latched", f"{ENC}.count")
    s += tag("pos", f"{ENC}.position-latched")
    # back to idle, then the active edge again: latch is used up
    s += drive(board, str(PRB), idle) + "simrun 1ms\n" + drive(board, str(PRB), active)
    s += "simrun 2ms\n"
    s += tag("again", f"{ENC}.count-latched")
    out = run_ok(tmp_path, s)
    v = values(out)
    assert num(v, "armed", 0) == 1
    assert num(v, "armed", 2) == 0, "an edge latched before probe-enable"
    armed_count, after_count = num(v, "armed", 1), num(v, "after", 2)
    latched = num(v, "after", 1)
    assert num(v, "after", 0) == 0, "probe-enable not reset by the latch"
    # 20000 counts/s: the latch happened between the two reads (2 ms = 40 counts)
    assert armed_count < latched < after_count, (armed_count, latched, after_count)
    assert after_count - latched == pytest.approx(40, abs=3)
    assert num(v, "pos", 0) == pytest.approx(latched / 4)
    assert num(v, "again", 0) == latched


def test_index_mask(tmp_path: Path, board: Path) -> None:
    """index-mask = 1: an index with the IndexMask pin at the wrong level is
    ignored (index-enable stays 1); at the right level it resets the count.
    The level is the register's (spec §9.5, CCR bit 8 IndexMaskPol, which the
    driver sets from index-mask-invert): index-mask-invert = 0 lets the index
    through while the pin is low, = 1 while it is high.  hostmot2(9) words it
    the other way round (docs/hm2-firmware.md, "Differences")."""
    s = load(board, CONFIG) + f"setp {ENC}.index-mask 1\nsetp {ENC}.index-invert 1\n"
    s += drive(board, str(MASK), "high")
    # an index every 100 counts at 20000 counts/s: every 5 ms
    s += probe(board, "quad", A, B, 20000, IDX, 100)
    s += f"simrun 2ms\nsetp {ENC}.index-enable 1\nsimrun 12ms\n"
    s += tag("masked", f"{ENC}.index-enable", f"{ENC}.count")
    s += drive(board, str(MASK), "low") + "simrun 8ms\n"
    s += tag("open", f"{ENC}.index-enable", f"{ENC}.count")
    s += f"setp {ENC}.index-mask-invert 1\nsetp {ENC}.index-enable 1\nsimrun 12ms\n"
    s += tag("inverted", f"{ENC}.index-enable")
    s += drive(board, str(MASK), "high") + "simrun 8ms\n"
    s += tag("inverted_open", f"{ENC}.index-enable")
    out = run_ok(tmp_path, s)
    v = values(out)
    assert num(v, "masked", 0) == 1 and num(v, "masked", 1) > 250
    assert num(v, "open", 0) == 0
    assert 0 <= num(v, "open", 1) < 130  # restarted at an index
    assert num(v, "inverted", 0) == 1
    assert num(v, "inverted_open", 0) == 0


@pytest.mark.parametrize("rate,per_s", [(20000.0, -5000.0), (-8000.0, 2000.0)])
def test_counter_mode(tmp_path: Path, board: Path, rate: float, per_s: float) -> None:
    """counter-mode = 1 counts A's rising edges, B = 1 up, B = 0 down. A
    quadrature signal has one A rise per 4 counts: forward, A rises while B
    is low (down), backward while B is high (up)."""
    s = load(board, CONFIG) + f"setp {ENC}.counter-mode 1\nsimrun 1ms\n"
    s += probe(board, "quad", A, B, rate) + "simrun 2ms\n"
    s += tag("a", f"{ENC}.count") + "simrun 20ms\n" + tag("b", f"{ENC}.count")
    v = values(run_ok(tmp_path, s))
    assert num(v, "b", 0) - num(v, "a", 0) == pytest.approx(per_s * 0.020, abs=2)


def test_quad_error_and_inputs(tmp_path: Path, board: Path) -> None:
    """A and B changing in the same clock is a quadrature error: reported
    on quad-error while quad-error-enable is set (once in the log), cleared
    by disabling and re-enabling; input-a/-b/-index show the pin levels."""
    s = load(board, CONFIG)
    s += drive(board, f"{A},{B},{IDX}", "low") + "simrun 2ms\n"
    s += tag("low", f"{ENC}.input-a", f"{ENC}.input-b", f"{ENC}.input-index")
    s += drive(board, f"{A},{IDX}", "high") + "simrun 2ms\n"
    s += tag("mixed", f"{ENC}.input-a", f"{ENC}.input-b", f"{ENC}.input-index")
    s += drive(board, str(A), "low") + "simrun 2ms\n"
    # an error while reporting is disabled: not shown
    s += drive(board, f"{A},{B}", "high") + "simrun 2ms\n"
    s += tag("disabled", f"{ENC}.quad-error")
    s += f"setp {ENC}.quad-error-enable 1\nsimrun 2ms\n"
    s += tag("cleared", f"{ENC}.quad-error")
    s += drive(board, f"{A},{B}", "low") + "simrun 2ms\n"
    s += tag("error", f"{ENC}.quad-error")
    s += f"setp {ENC}.quad-error-enable 0\nsimrun 2ms\n"
    s += f"setp {ENC}.quad-error-enable 1\nsimrun 2ms\n"
    s += tag("reenabled", f"{ENC}.quad-error")
    out = run_ok(tmp_path, s)
    v = values(out)
    assert [num(v, "low", i) for i in range(3)] == [0, 0, 0]
    assert [num(v, "mixed", i) for i in range(3)] == [1, 0, 1]
    assert num(v, "disabled", 0) == 0
    assert num(v, "cleared", 0) == 0, "enabling did not clear the old error"
    assert num(v, "error", 0) == 1
    assert num(v, "reenabled", 0) == 0
    assert out.count("Encoder 0: quadrature count error") == 1, out


def test_low_speed_velocity_and_timeout(tmp_path: Path, board: Path) -> None:
    """50 counts/s with a 1 ms servo thread: a count every 20 reads; the
    velocity comes from the count timestamps (exact, not counts per
    period).  After the encoder stops the estimate only falls (at most
    1 count / time since the last count) and is 0 after vel-timeout."""
    s = load(board, CONFIG) + f"setp {ENC}.scale 10\nsetp {ENC}.vel-timeout 0.1\n"
    s += probe(board, "quad", A, B, 50) + "simrun 300ms\n"
    s += tag("moving", f"{ENC}.velocity")
    s += "simrun 7ms\n" + tag("moving2", f"{ENC}.velocity")
    s += probe(board, "quad", A, B, 0) + "simrun 60ms\n"
    s += tag("slowing", f"{ENC}.velocity")
    s += "simrun 100ms\n" + tag("stopped", f"{ENC}.velocity")
    v = values(run_ok(tmp_path, s))
    assert num(v, "moving", 0) == pytest.approx(5.0, rel=0.01)
    assert num(v, "moving2", 0) == pytest.approx(5.0, rel=0.01)
    slowing = num(v, "slowing", 0)
    # 1 count (0.1 units) over >= 60 ms since the last count: <= 1.67 units/s
    assert 0 < slowing <= 0.1 / 0.060 + 1e-9, slowing
    assert num(v, "stopped", 0) == 0


def test_swap_step_dir(tmp_path: Path, board: Path) -> None:
    """swap_step_dir (StepGen version 0x42): the step pulses come out on
    the Direction pin and the direction level on the Step pin."""
    sg = f"{PFX}.stepgen.00"
    s = load(board, CONFIG)
    for k, val in [
        ("steplen", 5000),
        ("stepspace", 5000),
        ("dirsetup", 5000),
        ("dirhold", 5000),
        ("position-scale", 1000),
        ("control-type", 1),
        ("maxaccel", 0),
        ("swap_step_dir", 1),
        ("enable", 1),
    ]:
        s += f"setp {sg}.{k} {val}\n"
    s += "simrun 2ms\n" + probe(board, "reset", f"{SG_STEP},{SG_DIR}")
    s += f"setp {sg}.velocity-cmd -5\nsimrun 10ms\n"
    s += probe(board, "probe", "swapped", f"{SG_STEP},{SG_DIR}")
    s += tag("c", f"{sg}.counts")
    out = run_ok(tmp_path, s)
    pins = probed(out, "swapped")
    counts = num(values(out), "c", 0)
    assert -51 <= counts <= -40  # 5000 steps/s for 10 ms, less the servo-period lag
    assert pins[0]["level"] == 1 and pins[0]["rising"] <= 1  # Step pin: direction (negative)
    assert pins[1]["rising"] == pytest.approx(-counts, abs=1)  # Dir pin: the steps
