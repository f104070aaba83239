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


def _biquad_rows(rng: random.Random) -> list[Row]:
    """Segments of 12 periods: enable falls for one period, then rises with a
    new type/f0/Q (coefficients are computed on the rising edge), with a
    step and noise on in."""
    cases = [
        (1, 100.0, 0.7071),
        (2, 60.0, 1.2),
        (1, 499.0, 0.7071),
        (1, 500.0, 0.7071),
        (1, 600.0, 0.9),
        (1, 50.0, 0.5),
        (1, 50.0, 0.500001),
        (1, 50.0, 2.0),
        (1, 50.0, 1.999),
        (2, 250.0, 0.6),
        (0, 100.0, 0.7071),
        (3, 100.0, 0.7),
        (1, 0.0, 0.7),
        (1, -20.0, 0.7),
        (1, NAN, 0.7),
        (1, 100.0, NAN),
        (2, 1e-3, 1.5),
        (1, 333.333, 0.9),
        (2, 10.0, 0.51),
        (1, 100.0, 0.3),
        (1, 100.0, 2.5),
        (0, 10.0, 0.7),
        (2, 100.0, 0.49),
        (1, 100.0, 2.01),
        (0, 10.0, 0.7),
        (1, INF, 0.7),
        (1, 100.0, INF),
        (1, -INF, 0.7),
    ]
    rows: list[Row] = []
    for typ, f0, q in cases:
        rows.append([0.0, 0, typ, f0, q])
        for i in range(11):
            x = 1.0 if i >= 1 else 0.0
            rows.append([x + round(rng.uniform(-0.2, 0.2), 6), 1, typ, f0, q])
    return rows


spec(
    Spec(
        "biquad",
        [("in", "f"), ("enable", "b"), ("type", "u"), ("f0", "f"), ("Q", "f")],
        [("out", "f"), ("valid", "b"), ("s1", "f"), ("s2", "f")],
        _biquad_rows,
        setps=[{}, {"n0": "0.5", "n1": "0.3", "n2": "0.2", "d1": "-0.4", "d2": "0.1"}],
        note="coefficients per type on enable's rising edge, invalid f0/Q, type 0",
    )
)


spec(
    Spec(
        "biquad",
        [("in", "f"), ("enable", "b"), ("type", "u"), ("f0", "f"), ("Q", "f")],
        [("out", "f"), ("valid", "b"), ("s1", "f"), ("s2", "f")],
        _biquad_rows,
        note="the same inputs on a 250 us thread (sample rate 4 kHz)",
        period=250000,
        test="biquad-period",
    )
)


def _spindle_rows(rng: random.Random) -> list[Row]:
    """Velocity commands (rev/s at scale 1) with index-enable pulses."""
    rows: list[Row] = []
    vels = [0.0, 50.0, 50.0, 123.4, -80.0, 600.0, 1000.0, -1000.0, 0.5, NAN, 20.0, INF, 7.0]
    for v in vels:
        for i in range(24):
            rows.append([v, 1])
    return rows


spec(
    Spec(
        "sim_spindle",
        [("velocity-cmd", "f"), ("index-enable", "b")],
        [("position-fb", "f"), ("index-enable", "b")],
        _spindle_rows,
        setps=[{}, {"scale": "0.0166666667"}, {"scale": "-2.5"}, {"scale": "0.01"}],
        note="position from velocity-cmd x scale, index-enable cleared at whole revolutions",
        io=["index-enable"],
    )
)


def _thc_rows(rng: random.Random) -> list[Row]:
    """Segments: arc voltage around the request, velocity in/out of tolerance,
    torch/arc-ok/enable toggles, Z moving up and down."""
    rows: list[Row] = []
    z = 10.0
    for seg in range(14):
        en = 0 if seg in (0, 5) else 1
        torch = 0 if seg in (6, 7, 8, 12) else 1
        ok = 0 if seg in (3, 12) else 1
        req = 100.0
        for i in range(20):
            cur = req if seg not in (2, 9) else req * (0.5 if seg == 2 else 0.97)
            volts_target = [
                120.0,
                95.0,
                80.0,
                130.0,
                100.5,
                90.0,
                70.0,
                130.0,
                100.0,
                110.0,
                85.0,
                100.0,
                140.0,
                60.0,
            ][seg]
            enc = (volts_target + rng.uniform(-0.5, 0.5)) * 10.0 + 2.0
            if seg in (7, 8):
                z += 0.05 if seg == 7 else -0.03
            elif seg == 11:
                z += 0.02
            rows.append([enc, cur, req, 100.0, rng.choice([5.0, 2.0]), torch, ok, en, z])
    rows.append([NAN, 100.0, 100.0, 100.0, 5.0, 1, 1, 1, z])
    rows.append([1002.0, NAN, 100.0, 100.0, 5.0, 1, 1, 1, z])
    rows.append([1002.0, 100.0, 0.0, 100.0, 5.0, 1, 1, 1, z])
    return rows


def _thc_torch_rows(rng: random.Random) -> list[Row]:
    """Torch-off removal of the correction in both signs, at positive,
    zero and negative Z, and what a torch-on, disabled or not-at-speed
    period does to the remembered Z; the corner-lock boundary."""
    rows: list[Row] = []

    def seg(
        n: int,
        enc: float,
        torch: int,
        ok: int,
        en: int,
        z: float,
        cur: float = 100.0,
        req: float = 100.0,
        dz: float = 0.0,
    ) -> None:
        for i in range(n):
            rows.append([enc, cur, req, 100.0, 5.0, torch, ok, en, z + dz * (i + 1)])

    for z in (10.0, -5.0):
        for enc in (902.0, 1102.0):  # build the correction up / down
            for dz in (0.0, 0.01, -0.01):
                seg(20, enc, 1, 1, 1, z)
                seg(6, 1002.0, 0, 1, 1, z, dz=dz)
                seg(1, 1002.0, 1, 1, 1, z)
    seg(5, 1102.0, 1, 1, 1, -5.0)
    seg(3, 1002.0, 0, 1, 1, -5.0, dz=-0.01)
    seg(1, 1002.0, 1, 0, 1, -4.9)  # torch on, arc not ok
    seg(2, 1002.0, 0, 1, 1, -4.9, dz=0.01)
    seg(1, 1002.0, 1, 1, 1, -4.8, cur=50.0)  # torch on, not at speed
    seg(2, 1002.0, 0, 1, 1, -4.8, dz=0.01)
    seg(1, 1002.0, 0, 1, 0, -4.7)  # disabled, torch off
    seg(2, 1002.0, 0, 1, 1, -4.6, dz=0.01)
    seg(2, 902.0, 1, 1, 0, -4.6)  # disabled, torch on
    seg(2, 1002.0, 0, 1, 1, -4.5, dz=0.01)
    seg(3, 1002.0, 0, 1, 1, 0.0)
    for req in (100.0, -100.0, 0.0, 50.0, -0.0):
        for cur in (150.0, 100.0, 96.0, 95.0, 0.0, -0.0, -96.0, -100.0):
            seg(1, 902.0, 1, 1, 1, 0.0, cur=cur, req=req)
    return rows


spec(
    Spec(
        "thc",
        [
            ("encoder-vel", "f"),
            ("current-vel", "f"),
            ("requested-vel", "f"),
            ("volts-requested", "f"),
            ("vel-tol", "f"),
            ("torch-on", "b"),
            ("arc-ok", "b"),
            ("enable", "b"),
            ("z-pos-in", "f"),
        ],
        [
            ("z-pos-out", "f"),
            ("z-fb-out", "f"),
            ("volts", "f"),
            ("vel-status", "b"),
            ("offset-value", "f"),
        ],
        _thc_torch_rows,
        setps=[
            {
                "vel-scale": "0.1",
                "scale-offset": "2.0",
                "velocity-tol": "4",
                "voltage-tol": "1.5",
                "correction-vel": "0.002",
            }
        ],
        singleton=True,
        test="thc-torch",
        note="torch-off removal of the correction, the remembered Z, corner-lock edges",
    )
)


spec(
    Spec(
        "thc",
        [
            ("encoder-vel", "f"),
            ("current-vel", "f"),
            ("requested-vel", "f"),
            ("volts-requested", "f"),
            ("vel-tol", "f"),
            ("torch-on", "b"),
            ("arc-ok", "b"),
            ("enable", "b"),
            ("z-pos-in", "f"),
        ],
        [
            ("z-pos-out", "f"),
            ("z-fb-out", "f"),
            ("volts", "f"),
            ("vel-status", "b"),
            ("offset-value", "f"),
        ],
        _thc_rows,
        setps=[
            {
                "vel-scale": "0.1",
                "scale-offset": "2.0",
                "velocity-tol": "4",
                "voltage-tol": "1.5",
                "correction-vel": "0.002",
            }
        ],
        singleton=True,
        note="volts from encoder-vel, corner lock, correction up/down, removal on the way up",
    )
)


def _sim_encoder_rows(rng: random.Random) -> list[Row]:
    """Segments of 30 periods at one speed: slow and fast both ways, beyond
    the one-step-per-period limit, NaN and infinities."""
    speeds = [
        0.0,
        1.0,
        10.0,
        0.37,
        -1.0,
        250.0,
        1000.0,
        3000.0,
        -3000.0,
        NAN,
        5.0,
        INF,
        2.0,
        -INF,
        1.0,
    ]
    # first: 19999 counts/s at ppr 100 (20001 at scale 0.9999), then a crawl:
    # the first period assumes a 50 us make-pulses period as 2.9 does
    return [[49.9975]] + [[1.164153218e-5]] * 20 + [[v] for v in speeds for _ in range(30)]


_SE_PINS = [("phase-A", "b"), ("phase-B", "b"), ("phase-Z", "b"), ("rawcounts", "s")]

spec(
    Spec(
        "sim_encoder",
        [("speed", "f")],
        _SE_PINS,
        _sim_encoder_rows,
        setps=[
            {},
            {"ppr": "1"},
            {"ppr": "3", "scale": "60"},
            {"ppr": "7", "scale": "-2"},
            {"scale": "0.9999"},
        ],
        functs=[],
        gfuncts=["update-speed", "make-pulses"],
        load="num_chan=5",
        note="quadrature, index and rawcounts per period, speeds beyond the limit, first period",
    )
)


def _sim_encoder_fine_rows(rng: random.Random) -> list[Row]:
    """A non-zero speed from the first period on, then random speeds held
    for random stretches, with sign changes."""
    rows: list[Row] = []
    while len(rows) < 400:
        v = rng.choice([round(rng.uniform(-8, 8), 4), round(rng.uniform(-0.5, 0.5), 5), 1e-6])
        rows += [[v]] * rng.randint(5, 40)
    return [[3.5]] * 10 + rows[:400]


spec(
    Spec(
        "sim_encoder",
        [("speed", "f")],
        _SE_PINS + [("scale", "f")],
        _sim_encoder_fine_rows,
        setps=[
            {"scale": "1e-21"},
            {"scale": "-1e-20", "ppr": "1"},
            {"scale": "nan"},
            {"scale": "0.25", "ppr": "3"},
        ],
        functs=[],
        gfuncts=["update-speed", "make-pulses"],
        load="num_chan=4",
        period=50000,
        test="sim_encoder-scale",
        note="50 us thread: tiny/NaN scales (scale written back), random speeds",
    )
)


spec(
    Spec(
        "sim_encoder",
        [("speed", "f")],
        _SE_PINS,
        _sim_encoder_fine_rows,
        setps=[
            {"ppr": "0"},
            {"ppr": "4294967295", "scale": "1e12"},
            {"ppr": "2"},
            {"scale": "inf"},
        ],
        functs=[],
        gfuncts=["update-speed", "make-pulses"],
        load="num_chan=4",
        period=37000,
        test="sim_encoder-ppr",
        note="37 us thread: ppr 0 and 2^32-1, infinite scale, random speeds",
    )
)
