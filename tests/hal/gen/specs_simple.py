# SPDX-License-Identifier: GPL-2.0-or-later
"""Behaviour-test specs of the simple components (used by comp_cases.py)."""

from __future__ import annotations

import random

from comp_cases import INF, NAN, Row, Spec, floats, rows_of, spec, specials


def _mix(rng: random.Random, ncols: int, n: int, lo: float = -10, hi: float = 10) -> list[Row]:
    """Rows: every special value in each column, then random values."""
    sp = specials()
    rows: list[Row] = []
    for c in range(ncols):
        for v in sp:
            r = floats(rng, ncols, lo, hi)
            r[c] = v
            rows.append(r)
    rows += [floats(rng, ncols, lo, hi) for _ in range(n)]
    return rows


spec(
    Spec(
        "blend",
        [("in1", "f"), ("in2", "f"), ("select", "f")],
        [("out", "f")],
        lambda r: [
            x[:2] + [round(r.uniform(-0.5, 1.5), 6) if i >= 33 else x[2]]
            for i, x in enumerate(_mix(r, 3, 60))
        ],
        setps=[{}, {"open": "1"}],
        note="interpolation, clamped and open, NaN/inf",
    )
)

spec(
    Spec(
        "deadzone",
        [("in", "f")],
        [("out", "f")],
        lambda r: _mix(r, 1, 60, -4, 6),
        setps=[{}, {"center": "2.5", "threshold": "3"}, {"threshold": "-1"}, {"threshold": "0"}],
        note="default, shifted centre, negative and zero threshold",
    )
)

spec(
    Spec(
        "hypot",
        [("in0", "f"), ("in1", "f"), ("in2", "f")],
        [("out", "f")],
        lambda r: _mix(r, 3, 40),
        note="sqrt(in0^2+in1^2+in2^2), NaN/inf",
    )
)

spec(
    Spec(
        "offset",
        [("offset", "f"), ("in", "f"), ("fb-in", "f")],
        [("out", "f"), ("fb-out", "f")],
        lambda r: _mix(r, 3, 30),
        functs=["update-output", "update-feedback"],
        note="both functions",
    )
)

spec(
    Spec(
        "integ",
        [("in", "f"), ("gain", "f"), ("reset", "b"), ("max", "f"), ("min", "f")],
        [("out", "f")],
        lambda r: rows_of(
            [
                floats(r, 40, -5, 5) + [NAN, 1.0, 2.0, INF, 1.0, -INF, 3.0] * 2,
                [1.0] * 20 + [2.5, -1.0, 0.0] * 10,
                [0] * 30 + [1, 0, 0, 0, 0, 1, 1, 0, 0, 0],
                [1e20] * 40 + [0.004, 1e20, 0.002],
                [-1e20] * 45 + [-0.001, 0.003],
            ]
        ),
        setps=[{}],
        note="integral of gain*in, reset, min/max windup limits",
    )
)

spec(
    Spec(
        "invert",
        [("in", "f")],
        [("out", "f")],
        lambda r: _mix(r, 1, 30, -2, 2) + [[x] for x in (1e-9, -1e-9, 0.05, -0.05, 0.1, -0.1)],
        setps=[{}, {"deadband": "0.1"}, {"deadband": "-1"}, {"deadband": "1e-12"}],
        note="1/in with deadband",
    )
)

spec(
    Spec(
        "clarke2",
        [("a", "f"), ("b", "f")],
        [("x", "f"), ("y", "f")],
        lambda r: _mix(r, 2, 30),
        note="two-phase Clarke transform",
    )
)

spec(
    Spec(
        "clarke3",
        [("a", "f"), ("b", "f"), ("c", "f")],
        [("x", "f"), ("y", "f"), ("h", "f")],
        lambda r: _mix(r, 3, 30),
        note="three-phase Clarke transform",
    )
)

spec(
    Spec(
        "clarkeinv",
        [("x", "f"), ("y", "f"), ("h", "f"), ("theta", "f")],
        [("a", "f"), ("b", "f"), ("c", "f")],
        lambda r: _mix(r, 4, 40, -2, 2),
        note="inverse Clarke with rotation",
    )
)

spec(
    Spec(
        "feedcomp",
        [("in", "f"), ("enable", "b"), ("vel", "f")],
        [("out", "f")],
        lambda r: [[x[0], i % 3 != 0, x[2]] for i, x in enumerate(_mix(r, 3, 30, -50, 150))],
        setps=[{"feed": "0"}, {"feed": "100"}, {"feed": "-7.5"}],
        note="in * vel / feed when enabled",
    )
)

spec(
    Spec(
        "gearchange",
        [("sel", "b"), ("speed-in", "f"), ("dir-in", "b")],
        [("speed-out", "f"), ("dir-out", "b")],
        lambda r: [
            [i % 2, x, (i // 2) % 2]
            for i, x in enumerate(
                [
                    0.0,
                    50.0,
                    -50.0,
                    99.0,
                    150000.0,
                    -150000.0,
                    NAN,
                    INF,
                    -INF,
                    500.0,
                    1000.0,
                    20000.0,
                    -3.0,
                ]
                + floats(r, 30, -3000, 60000)
            )
        ],
        setps=[
            {},
            {
                "min1": "100",
                "max1": "3000",
                "min2": "500",
                "max2": "6000",
                "scale2": "2.5",
                "reverse": "1",
            },
            {"scale2": "0.5"},
            {"min2": "-10", "max2": "10", "scale2": "4"},
        ],
        note="gear 1/2 scaling, clamping, reverse",
    )
)

spec(
    Spec(
        "ilowpass",
        [("in", "s")],
        [("out", "s")],
        lambda r: [
            [v]
            for v in [
                0,
                1000,
                1000,
                1000,
                1000,
                1000,
                -2000,
                -2000,
                2147483647,
                2147483647,
                -2147483648,
                -2147483648,
                5,
                5,
                5,
            ]
            + [r.randint(-100000, 100000) for _ in range(30)]
        ],
        setps=[
            {},
            {"gain": "0.1", "scale": "1"},
            {"gain": "1.5"},
            {"gain": "-1"},
            {"scale": "1e6"},
        ],
        note="integer low-pass, scale and gain incl. out-of-range",
    )
)

spec(
    Spec(
        "joyhandle",
        [("in", "f")],
        [("out", "f")],
        lambda r: _mix(r, 1, 40, -1.3, 1.3) + [[x] for x in (0.05, -0.05, 0.1, -0.1, 0.5)],
        setps=[
            {},
            {"deadband": "0.1", "power": "3", "scale": "2", "offset": "0.5"},
            {"inverse": "1"},
            {"inverse": "1", "deadband": "0.2", "power": "1.5"},
            {"power": "0.5"},
            {"deadband": "0.99"},
            {"deadband": "1.5"},
            {"power": "1", "deadband": "0.1"},
            {"inverse": "1", "scale": "2", "offset": "0.5", "deadband": "0.1"},
            {"deadband": "-0.2", "scale": "-3", "offset": "-0.25"},
        ],
        note="nonlinear joystick curve with deadband, scale, offset, inverse",
    )
)

spec(
    Spec(
        "knob2float",
        [("counts", "s"), ("enable", "b"), ("scale", "f")],
        [("out", "f")],
        lambda r: rows_of(
            [
                [
                    7,
                    10,
                    20,
                    30,
                    30,
                    25,
                    200,
                    300,
                    -500,
                    -600,
                    1000,
                    1010,
                    1020,
                    2147483647,
                    -2147483648,
                    5,
                    10,
                    15,
                    20,
                    25,
                    30,
                ],
                [1, 1, 1, 1, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 1, 1],
                [0.01] * 14 + [0.1, 0.1, -0.5, 0.2, NAN, 0.01, 0.01],
            ]
        ),
        setps=[{}, {"max-out": "5", "min-out": "-5"}, {"max-out": "-1", "min-out": "1"}],
        note="count deltas scaled into out, clamped to min-out..max-out",
    )
)

spec(
    Spec(
        "minmax",
        [("in", "f"), ("reset", "b")],
        [("max", "f"), ("min", "f")],
        lambda r: [
            [x, i in (10, 11, 30)]
            for i, x in enumerate(floats(r, 20) + [NAN, 3.0, INF, -1.0, -INF, 2.0] + floats(r, 15))
        ],
        note="running max/min and reset",
    )
)

spec(
    Spec(
        "sphereprobe",
        [("px", "s"), ("py", "s"), ("pz", "s"), ("cx", "s"), ("cy", "s"), ("cz", "s"), ("r", "s")],
        [("probe-out", "b")],
        lambda r: [
            [
                r.randint(-60, 60),
                r.randint(-60, 60),
                r.randint(-60, 60),
                5,
                -3,
                2,
                r.choice([0, 10, 40, 50]),
            ]
            for _ in range(60)
        ]
        + [
            [0, 0, 0, 0, 0, 0, 0],
            [40000, 0, 0, 0, 0, 0, 40000],
            [0, 0, -30, 0, 0, 0, 40],
            [0, 0, 30, 0, 0, 0, 40],
            [46341, 46341, 46341, 0, 0, 0, 46341],
            [2147483647, 0, 0, -2147483648, 0, 0, 2147483647],
        ],
        note="inside the hemisphere above the centre",
    )
)
