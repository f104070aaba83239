# SPDX-License-Identifier: GPL-2.0-or-later
"""Every hm2 module through the real driver (hostmot2 + hm2_sim) and the
real Verilog (SVST8_4 on a virtual 5i20), measured on the FPGA pins.

References: the HAL/driver semantics of LinuxCNC's hostmot2 (docs/hostmot2.md,
the seed's hostmot2 manual): GPIO out/invert/open drain, stepgen step
timing parameters and rates, encoder counts = counts of the quadrature
source, pwmgen duty = value/scale per output type, watchdog bite after
timeout_ns without a write.  Simulated durations stay short: the board runs
at a few percent of real time."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from hm2e2e import (
    ENC0_A,
    ENC0_B,
    ENC0_IDX,
    PFX,
    PWM0_NENA,
    PWM0_OUT0,
    PWM0_OUT1,
    SG0_DIR,
    SG0_STEP,
    halrun,
    load,
    needs_vboard,
    num,
    probe,
    probed,
    tag,
    values,
    vboard,
)

pytestmark = needs_vboard

CLOCK_LOW_NS = 1e9 / 33_333_333  # one 5i20 ClockLow period


@pytest.fixture
def board(tmp_path: Path) -> Iterator[Path]:
    with vboard.VBoardProcess(tmp_path / "b.sock", "5i20", "SVST8_4") as vb:
        yield Path(vb.socket_path)
        assert vb.proc.poll() is None


def run_ok(tmp: Path, script: str) -> str:
    r = halrun(tmp, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert "failed" not in out, out
    return out


def test_gpio_out_invert_opendrain_in(tmp_path: Path, board: Path) -> None:
    g = f"{PFX}.gpio"
    s = load(board)
    # pin 0: push-pull output; pin 4: open drain; pin 6: inverted; pin 1: input
    s += f"setp {g}.000.is_output 1\nsetp {g}.000.out 1\n"
    s += f"setp {g}.004.is_output 1\nsetp {g}.004.is_opendrain 1\nsetp {g}.004.out 0\n"
    s += f"setp {g}.006.is_output 1\nsetp {g}.006.invert_output 1\nsetp {g}.006.out 0\n"
    s += probe(board, "drive", 1, "high")
    s += "simrun 2ms\n"
    s += probe(board, "probe", "a", "0,4,6,1")
    s += tag("in_a", f"{g}.001.in", f"{g}.001.in_not")
    s += f"setp {g}.000.out 0\nsetp {g}.004.out 1\nsetp {g}.006.out 1\n"
    s += probe(board, "drive", 1, "low")
    s += "simrun 2ms\n"
    s += probe(board, "probe", "b", "0,4,6,1")
    s += tag("in_b", f"{g}.001.in", f"{g}.001.in_not")
    out = run_ok(tmp_path, s)
    a, b = probed(out, "a"), probed(out, "b")
    # push-pull follows out
    assert (a[0]["oe"], a[0]["level"]) == (1, 1)
    assert (b[0]["oe"], b[0]["level"]) == (1, 0)
    # open drain: out=0 pulls low, out=1 releases (the pull-up reads high)
    assert (a[1]["oe"], a[1]["level"]) == (1, 0)
    assert (b[1]["oe"], b[1]["level"]) == (0, 1)
    # inverted output
    assert (a[2]["oe"], a[2]["level"]) == (1, 1)
    assert (b[2]["oe"], b[2]["level"]) == (1, 0)
    # the input follows the external drive
    assert a[3]["oe"] == 0 and b[3]["oe"] == 0
    v = values(out)
    assert (num(v, "in_a", 0), num(v, "in_a", 1)) == (1, 0)
    assert (num(v, "in_b", 0), num(v, "in_b", 1)) == (0, 1)


def stepgen_setup(board: Path, steplen: int = 5000, stepspace: int = 5000) -> str:
    sg = f"{PFX}.stepgen.00"
    s = load(board)
    for k, val in [
        ("steplen", steplen),
        ("stepspace", stepspace),
        ("dirsetup", 20000),
        ("dirhold", 20000),
        ("position-scale", 1000),
        ("maxvel", 40),
        ("maxaccel", 2000),
        ("enable", 1),
    ]:
        s += f"setp {sg}.{k} {val}\n"
    return s


def test_stepgen_position_mode(tmp_path: Path, board: Path) -> None:
    sg = f"{PFX}.stepgen.00"
    s = stepgen_setup(board, steplen=6000, stepspace=4000)
    s += f"setp {sg}.position-cmd 0.1\n"
    s += probe(board, "reset", SG0_STEP)
    s += "simrun 50ms\n"
    s += tag("fb", f"{sg}.counts", f"{sg}.position-fb")
    s += probe(board, "probe", "p", f"{SG0_STEP},{SG0_DIR}")
    out = run_ok(tmp_path, s)
    v = values(out)
    # the driver's feedback is the step accumulator: 0.1 within a step,
    # counts its integer part (LinuxCNC's floor: 99 when just below 100)
    assert num(v, "fb", 1) == pytest.approx(0.1, abs=0.0011)
    assert abs(num(v, "fb", 0) - 100) <= 1
    step = probed(out, "p")[0]
    assert step["rising"] == num(v, "fb", 0)  # the pins carried exactly the steps counted
    # step timing on the pin: high >= steplen, low >= stepspace (one clock of rounding)
    assert 6000 - CLOCK_LOW_NS <= step["min_high_ns"] <= 6000 + 2 * CLOCK_LOW_NS
    assert step["min_low_ns"] >= 4000 - CLOCK_LOW_NS
    # maxvel 40 units/s = 40000 steps/s: no step period shorter than 25 us (1 % margin)
    assert step["min_high_ns"] + step["min_low_ns"] >= 25000 * 0.99


def test_stepgen_velocity_mode(tmp_path: Path, board: Path) -> None:
    sg = f"{PFX}.stepgen.00"
    s = stepgen_setup(board)
    s += f"setp {sg}.control-type 1\nsetp {sg}.velocity-cmd 5\n"
    s += "simrun 10ms\n"  # accelerate (2.5 ms at 2000 units/s^2)
    s += probe(board, "reset", SG0_STEP)
    s += tag("c0", f"{sg}.counts")
    s += "simrun 10ms\n"
    s += tag("c1", f"{sg}.counts", f"{sg}.velocity-fb")
    s += probe(board, "probe", "fwd", f"{SG0_STEP},{SG0_DIR}")
    s += f"setp {sg}.velocity-cmd -5\n"
    s += "simrun 15ms\n"
    s += tag("c2", f"{sg}.counts", f"{sg}.velocity-fb")
    s += probe(board, "probe", "rev", f"{SG0_STEP},{SG0_DIR}")
    out = run_ok(tmp_path, s)
    v = values(out)
    # 5 units/s x 1000 steps/unit over 10 ms: 50 steps, 200 us apart on the pin
    assert num(v, "c1", 0) - num(v, "c0", 0) == pytest.approx(50, abs=1)
    assert num(v, "c1", 1) == pytest.approx(5, rel=0.02)
    fwd, rev = probed(out, "fwd"), probed(out, "rev")
    assert fwd[0]["period_ns"] == pytest.approx(200_000, rel=0.005)
    assert fwd[0]["rising"] == pytest.approx(50, abs=1)
    assert num(v, "c2", 1) == pytest.approx(-5, rel=0.02)
    assert num(v, "c2", 0) < num(v, "c1", 0)
    assert rev[0]["period_ns"] == pytest.approx(200_000, rel=0.005)
    assert fwd[1]["level"] != rev[1]["level"]  # the direction pin flipped


@pytest.mark.parametrize("rate", [20000.0, -8000.0])
def test_encoder_counts_velocity(tmp_path: Path, board: Path, rate: float) -> None:
    e = f"{PFX}.encoder.00"
    s = load(board) + f"setp {e}.scale 100\n"
    s += probe(board, "quad", ENC0_A, ENC0_B, rate)
    s += "simrun 5ms\n"
    s += tag("a", f"{e}.count")
    s += "simrun 10ms\n"
    s += tag("b", f"{e}.count", f"{e}.velocity", f"{e}.position")
    out = run_ok(tmp_path, s)
    v = values(out)
    delta = num(v, "b", 0) - num(v, "a", 0)
    assert delta == pytest.approx(rate * 0.010, abs=2)
    assert num(v, "b", 1) == pytest.approx(rate / 100, rel=0.03)
    assert num(v, "b", 2) == pytest.approx(num(v, "b", 0) / 100)


def test_encoder_index(tmp_path: Path, board: Path) -> None:
    e = f"{PFX}.encoder.00"
    s = load(board)
    # index once every 100 counts at 20000 counts/s: every 5 ms
    s += probe(board, "quad", ENC0_A, ENC0_B, 20000, ENC0_IDX, 100)
    s += "simrun 2ms\n"
    s += f"setp {e}.index-enable 1\n"
    s += tag("armed", f"{e}.index-enable")
    s += "simrun 8ms\n"
    s += tag("after", f"{e}.index-enable", f"{e}.count")
    s += probe(board, "probe", "idx", ENC0_IDX)
    out = run_ok(tmp_path, s)
    v = values(out)
    assert num(v, "armed", 0) == 1
    assert num(v, "after", 0) == 0  # the driver cleared index-enable at the index
    # the count restarted at the index: fewer counts than since start (160)
    assert 0 <= num(v, "after", 1) < 110
    assert probed(out, "idx")[0]["rising"] >= 1


@pytest.mark.parametrize(
    "otype,value,duty0,duty1",
    [
        (1, 0.25, 0.25, None),  # PWM/Dir: Out0 duty, Out1 = direction (low: positive)
        (1, -0.6, 0.6, None),
        # Up/Down: this firmware puts negative values on Out0 and positive
        # ones on Out1 (spec/hostmot2.md, "Up/down PWM mode in this VHDL")
        (2, 0.3, 0.0, 0.3),
        (2, -0.3, 0.3, 0.0),
        (3, 0.4, 0.4, None),  # PDM: density on Out0
        (4, 0.35, None, 0.35),  # Dir/PWM: Out0 = direction, Out1 = PWM
        (4, -0.35, None, 0.35),
    ],
)
def test_pwmgen_duty(
    tmp_path: Path, board: Path, otype: int, value: float, duty0: float | None, duty1: float | None
) -> None:
    p = f"{PFX}.pwmgen"
    s = load(board)
    s += f"setp {p}.pwm_frequency 20000\nsetp {p}.pdm_frequency 2000000\n"
    s += f"setp {p}.00.output-type {otype}\nsetp {p}.00.scale 1\nsetp {p}.00.value {value}\n"
    s += f"setp {p}.00.enable 1\n"
    s += "simrun 2ms\n"
    s += probe(board, "reset", f"{PWM0_OUT0},{PWM0_OUT1},{PWM0_NENA}")
    s += "simrun 3ms\n"
    s += probe(board, "probe", "p", f"{PWM0_OUT0},{PWM0_OUT1},{PWM0_NENA}")
    out = run_ok(tmp_path, s)
    pins = probed(out, "p")
    duty = [pn["high_total_ns"] / pn["total_ns"] for pn in pins]
    for i, want in ((0, duty0), (1, duty1)):
        if want is not None:
            assert duty[i] == pytest.approx(want, abs=0.01)
        else:  # direction output: static, high for negative values
            assert pins[i]["rising"] + pins[i]["falling"] == 0
            assert pins[i]["level"] == (1 if value < 0 else 0)
    if otype == 1:
        assert pins[0]["period_ns"] == pytest.approx(50_000, rel=0.01)  # 20 kHz
    assert (pins[2]["oe"], pins[2]["level"]) == (1, 0)  # /enable driven low while enabled


def test_watchdog_bite_and_recovery(tmp_path: Path, board: Path) -> None:
    g, w = f"{PFX}.gpio", f"{PFX}.watchdog"
    s = load(board)
    s += f"setp {w}.timeout_ns 5000000\n"
    s += f"setp {g}.000.is_output 1\nsetp {g}.000.out 1\n"
    s += "simrun 3ms\n"
    s += probe(board, "probe", "running", 0)
    s += f"delf {PFX}.write servo\n"  # the host stops writing (and petting)
    s += "simrun 3ms\n"
    s += probe(board, "probe", "early", 0)  # ~3-4 ms since the last pet: not yet
    s += tag("bit_early", f"{w}.has_bit")
    s += "simrun 4ms\n"
    s += probe(board, "probe", "bitten", 0)  # > 5 ms: outputs are inputs now
    s += tag("bit", f"{w}.has_bit")
    s += f"addf {PFX}.write servo\n"
    s += "simrun 2ms\n"
    s += probe(board, "probe", "still", 0)  # writes alone do not re-arm it
    s += f"setp {w}.has_bit 0\n"
    s += "simrun 2ms\n"
    s += probe(board, "probe", "restored", 0)
    s += tag("bit_after", f"{w}.has_bit")
    r = halrun(tmp_path, s)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    v = values(out)
    assert (probed(out, "running")[0]["oe"], probed(out, "running")[0]["level"]) == (1, 1)
    assert probed(out, "early")[0]["oe"] == 1 and num(v, "bit_early") == 0
    assert probed(out, "bitten")[0]["oe"] == 0 and num(v, "bit") == 1
    assert probed(out, "still")[0]["oe"] == 0
    assert (probed(out, "restored")[0]["oe"], probed(out, "restored")[0]["level"]) == (1, 1)
    assert num(v, "bit_after") == 0


def test_simulated_clock_is_deterministic(tmp_path: Path) -> None:
    """Lockstep board + simulated HAL clock: two runs print identical values
    (stepgen feedback, encoder counts, velocities, pin edge counts)."""
    outs = []
    for run in range(2):
        d = tmp_path / f"run{run}"
        d.mkdir()
        with vboard.VBoardProcess(d / "b.sock", "5i20", "SVST8_4") as vb:
            sock = Path(vb.socket_path)
            sg, e = f"{PFX}.stepgen.00", f"{PFX}.encoder.00"
            s = stepgen_setup(sock)
            s += f"setp {sg}.control-type 1\nsetp {sg}.velocity-cmd 7.3\n"
            s += probe(sock, "quad", ENC0_A, ENC0_B, 12345.6)
            s += "simrun 7ms\n"
            s += tag(
                "v",
                f"{sg}.counts",
                f"{sg}.position-fb",
                f"{sg}.velocity-fb",
                f"{e}.count",
                f"{e}.velocity",
            )
            s += probe(sock, "probe", "p", f"{SG0_STEP},{ENC0_A}")
            out = run_ok(d, s)
            outs.append((values(out)["v"], values(out)["p"]))
    assert outs[0] == outs[1]
    assert float(outs[0][0][0]) > 0  # something moved


# A 4-phase table on stepgen 0's Step, Direction, Table2 and Table3 pins
# (48..51): phase k drives pin k and pin k+1 (mod 4), like a two-phase-on
# unipolar stepper sequence.  table-data-0 holds phases 0..3, one byte each.
TABLE = [0b0011, 0b0110, 0b1100, 0b1001]


def test_stepgen_table_mode(tmp_path: Path, board: Path) -> None:
    """step_type 4 = a 4-entry step table (hostmot2(9) step_type, table-data-N):
    after M steps the table pointer is at M mod 4, so the pins show table
    entry M mod 4; stepping back walks the table in reverse.  With
    stepgen_width=4 the pins above the table stay GPIO."""
    sg = f"{PFX}.stepgen.00"
    config = (
        "firmware=hm2/5i20/SVST8_4.BIT num_encoders=1 num_pwmgens=1 num_stepgens=1 "
        "stepgen_width=4"
    )
    s = load(board, config)
    for k, val in [
        ("steplen", 5000),
        ("stepspace", 5000),
        ("position-scale", 1000),
        ("maxvel", 40),
        ("maxaccel", 2000),
        ("step_type", 4),
        ("table-data-0", sum(v << (8 * i) for i, v in enumerate(TABLE))),
        ("enable", 1),
    ]:
        s += f"setp {sg}.{k} {val}\n"
    s += "simrun 5ms\n"
    s += probe(board, "probe", "p0", "48,49,50,51,52")
    s += probe(board, "reset", "48,49,50,51")
    steps = [7, 30, 29, 2]  # forward 7, forward 23, back 1, back 27
    for n, m in enumerate(steps):
        s += f"setp {sg}.position-cmd {m / 1000}\n"
        s += "simrun 40ms\n"
        s += tag(f"c{n}", f"{sg}.counts")
        s += probe(board, "probe", f"p{n + 1}", "48,49,50,51")
    out = run_ok(tmp_path, s)
    v = values(out)

    def phase(name: str) -> int:
        return sum(p["level"] << i for i, p in enumerate(probed(out, name)[:4]))

    # driven by the stepgen from the start (DDR + AltSource), showing entry 0
    p0 = probed(out, "p0")
    assert all(p["oe"] == 1 for p in p0[:4]) and phase("p0") == TABLE[0]
    assert p0[4]["oe"] == 0  # Table4 pin: beyond stepgen_width, a GPIO input
    counts = [int(num(v, f"c{n}", 0)) for n in range(len(steps))]
    for n, m in enumerate(steps):
        # counts is the integer part of the accumulator (LinuxCNC's floor):
        # the driver's position loop settles a hair below a target reached
        # from below, so it is m or m - 1; the pins took exactly that many
        # steps, and the table pointer is at counts mod 4
        assert abs(counts[n] - m) <= 1
        assert phase(f"p{n + 1}") == TABLE[counts[n] % 4], (m, counts[n])
    # two-phase-on: every step, either way, turns exactly one pin on; the
    # position loop may step forth and back at a target (pairs of steps)
    net = counts[0] + sum(abs(b - a) for a, b in zip(counts, counts[1:]))
    rises = sum(p["rising"] for p in probed(out, "p4"))
    assert rises >= net and (rises - net) % 2 == 0, (rises, net)
