# SPDX-License-Identifier: GPL-2.0-or-later
"""Behaviour-test specs of components that LinuxCNC 2.9's sample
configurations load (used by comp_cases.py; see docs/compat.md)."""

from __future__ import annotations

import random

from comp_cases import INF, NAN, Row, Spec, spec


def _home_rows(rng: random.Random) -> list[Row]:
    """Ramps through +-1 in 0.05 steps (both directions, over each
    instance's trip and release points), NaN and infinities, then random
    positions; index-enable is set in the first row only (an IO pin)."""
    pos: list[float] = []
    pos += [round(i * 0.05, 4) for i in range(40)]
    pos += [round(1.95 - i * 0.05, 4) for i in range(60)]
    pos += [round(-1.0 + i * 0.05, 4) for i in range(40)]
    pos += [1.2, 1.2, 0.7, NAN, 2.0, NAN, 0.0, -1.2, -0.7, INF, 0.5, -INF, 0.999, 1.0]
    pos += [round(rng.uniform(-2.0, 2.0), 3) for _ in range(60)]
    return [[p, 1.0 if i == 0 else 0.0] for i, p in enumerate(pos)]


spec(
    Spec(
        "sim_home_switch",
        [("cur-pos", "f"), ("index-enable", "b")],
        [("home-sw", "b"), ("index-enable", "b")],
        _home_rows,
        setps=[
            {},
            {"home-pos": "-0.5"},
            {"hysteresis": "0.5", "index-delay-ms": "50"},
            {"home-pos": "0", "index-delay-ms": "0"},
            {"hysteresis": "-0.5", "index-delay-ms": "2.5"},
            {"home-pos": "-1", "hysteresis": "-0.5", "index-delay-ms": "-1"},
            {"hysteresis": "0", "index-delay-ms": "0.5"},
            {"home-pos": "-1", "hysteresis": "nan"},
            {"home-pos": "nan"},
            {"home-pos": "inf", "index-delay-ms": "1e9"},
        ],
        io=["index-enable"],
        note="home-sw with hysteresis on both sides of 0, index-enable cleared after the delay",
    )
)


def _index_rows(rng: random.Random) -> list[Row]:
    return [[0.0, 1.0 if i == 0 else 0.0] for i in range(20)]


spec(
    Spec(
        "sim_home_switch",
        [("cur-pos", "f"), ("index-enable", "b")],
        [("index-enable", "b")],
        _index_rows,
        setps=[{"index-delay-ms": d} for d in ("0.1", "0.3", "0.4", "0.8", "1.0", "1.2")],
        io=["index-enable"],
        period=100000,
        test="sim_home_switch-delay",
        note="index-enable cleared after index-delay-ms at a 0.1 ms period",
    )
)
