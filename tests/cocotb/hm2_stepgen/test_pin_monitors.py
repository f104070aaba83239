# SPDX-License-Identifier: GPL-2.0-or-later
"""The pin monitors of tests/cocotb/common/pins.py on hand-made traces:
each rule they check must fire on a trace that breaks it and stay quiet on
one that keeps it (so the firmware tests that rely on them can fail)."""

from __future__ import annotations

import pytest

from common.pins import DutyMeter, StepLimits, Trace, check_stepdir, check_updown, decode_quadrature

P = 10.0  # clock period, ns


def tr(v0: int, *edges: tuple[float, int]) -> Trace:
    return Trace(0.0, v0, [(t * P, v) for t, v in edges])


def test_stepdir_clean_counts_both_ways() -> None:
    step = tr(0, (10, 1), (12, 0), (14, 1), (16, 0), (40, 1), (42, 0))
    dirn = tr(0, (25, 1))
    rep = check_stepdir(step, dirn, P, StepLimits(width=2, idle=2, setup=3, hold=3))
    assert rep.violations == []
    assert (rep.up, rep.down, rep.position) == (2, 1, 1)
    assert rep.widths == [2, 2, 2] and rep.holds == [9] and rep.setups == [15]


@pytest.mark.parametrize(
    "limits,needle",
    [
        (StepLimits(width=3, idle=1, setup=1, hold=1), "pulse width 2 < 3"),
        (StepLimits(width=1, idle=3, setup=1, hold=1), "pulse idle 2 < 3"),
        (StepLimits(width=1, idle=1, setup=16, hold=1), "dir setup 15 < 16"),
        (StepLimits(width=1, idle=1, setup=1, hold=10), "dir hold 9 < 10"),
    ],
)
def test_stepdir_each_rule_fires(limits: StepLimits, needle: str) -> None:
    step = tr(0, (10, 1), (12, 0), (14, 1), (16, 0), (40, 1), (42, 0))
    dirn = tr(0, (25, 1))
    rep = check_stepdir(step, dirn, P, limits)
    assert any(needle in v for v in rep.violations), rep.violations


def test_stepdir_dir_change_during_pulse_and_same_instant() -> None:
    rep = check_stepdir(tr(0, (10, 1), (14, 0)), tr(0, (12, 1)), P, StepLimits())
    assert any("during a step pulse" in v for v in rep.violations)
    rep = check_stepdir(tr(0, (10, 1), (14, 0)), tr(0, (10, 1)), P, StepLimits())
    assert any("dir setup 0" in v for v in rep.violations)


def test_updown() -> None:
    up = tr(0, (0, 1), (2, 0), (6, 1), (8, 0))
    down = tr(0, (3, 1), (5, 0))
    rep = check_updown(up, down, P, StepLimits(width=2, idle=1))
    assert rep.violations == [] and (rep.up, rep.down) == (2, 1)
    rep = check_updown(up, tr(0, (1, 1), (5, 0)), P, StepLimits())
    assert any("at once" in v for v in rep.violations)


def test_quadrature_decoder() -> None:
    # forward 00 -> 10 -> 11 -> 01 -> 00, then back one
    a = tr(0, (1, 1), (3, 0))
    b = tr(0, (2, 1), (4, 0), (6, 1))
    rep = decode_quadrature(a, b, P, min_state=1)
    assert rep.violations == [] and rep.position == 4 - 1 and rep.min_state == 1
    rep = decode_quadrature(a, b, P, min_state=2)
    assert any("lasted 1 < 2" in v for v in rep.violations)
    rep = decode_quadrature(tr(0, (1, 1)), tr(0, (1, 1)), P)
    assert any("illegal" in v for v in rep.violations)


def test_duty_meter() -> None:
    t = tr(0, (0, 1), (3, 0), (10, 1), (13, 0), (20, 1), (23, 0))
    m = DutyMeter(t)
    assert m.duty(0, 20 * P) == pytest.approx(0.3)
    assert m.high_time(1 * P, 11 * P) == pytest.approx(3 * P)
    assert m.periods(0, 100 * P) == [10 * P, 10 * P]
    assert m.pulses(0, 15 * P) == 2
    assert m.high_widths(0, 100 * P) == [3 * P] * 3
    with pytest.raises(ValueError):
        m.duty(5, 5)
