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


def _gray_rows(rng: random.Random) -> list[Row]:
    edge = [0, 1, 2, 3, 4, 7, 8, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFE, 0xFFFFFFFF, 0xAAAAAAAA]
    return [[float(v)] for v in edge + [rng.randrange(1 << 32) for _ in range(40)]]


spec(
    Spec(
        "bin2gray",
        [("in", "u")],
        [("out", "u")],
        _gray_rows,
        setps=[{}, {}],
        note="Gray code of edge values and random numbers",
    )
)


def _corexy_rows(rng: random.Random) -> list[Row]:
    sp = [0.0, -0.0, 1.0, -1.0, 1e-300, 1e300, -1e300, NAN, INF, -INF]
    rows: list[Row] = []
    for c in range(4):
        for v in sp:
            r = [round(rng.uniform(-100, 100), 6) for _ in range(4)]
            r[c] = v
            rows.append(r)
    rows += [[round(rng.uniform(-500, 500), 6) for _ in range(4)] for _ in range(40)]
    return rows


spec(
    Spec(
        "corexy_by_hal",
        [("j0-motor-pos-cmd", "f"), ("j1-motor-pos-cmd", "f"), ("alpha-fb", "f"), ("beta-fb", "f")],
        [("alpha-cmd", "f"), ("beta-cmd", "f"), ("j0-motor-pos-fb", "f"), ("j1-motor-pos-fb", "f")],
        _corexy_rows,
        note="motor commands from joint commands and joint feedback from motor feedback",
    )
)

_PP_OUT = ["01", "02", "03", "04", "05", "06", "07", "08", "09", "14", "16", "17"]
_PP_IN = ["02", "03", "04", "05", "06", "07", "08", "09", "10", "11", "12", "13", "15"]


def _parport_rows(rng: random.Random, n: int) -> list[Row]:
    rows: list[Row] = [[0.0] * n, [1.0] * n]
    rows += [[float(1 << i == 1 << k) for i in range(n)] for k in range(n)]
    rows += [[float(rng.random() < 0.5) for _ in range(n)] for _ in range(20)]
    return rows


def _parport_spec(test: str, outs: list[str], ins: list[str], note: str) -> None:
    """One test of some of the pins (the streamer and sampler take at most 21
    values a row)."""
    setps = {f"pin-{p}-out-invert": "1" for p in outs[::3]}
    setps.update({"pin-02-out-reset": "1", "reset-time": "5000"})
    spec(
        Spec(
            "sim_parport",
            [(f"pin-{p}-out", "b") for p in outs] + [(f"pin-{p}-in-fake", "b") for p in ins],
            [(f"pin-{p}-out-fake", "b") for p in outs]
            + [(f"pin-{p}-in", "b") for p in ins]
            + [(f"pin-{p}-in-not", "b") for p in ins],
            lambda rng: _parport_rows(rng, len(outs) + len(ins)),
            setps=[setps],
            functs=["read", "write", "reset"],
            prefix="parport.0",
            singleton=True,
            load="names=parport.0",
            test=test,
            note=note,
        )
    )


_parport_spec("sim_parport-out", _PP_OUT, [], "out to out-fake, inverted by -invert (write)")
_parport_spec("sim_parport-in", [], _PP_IN[:8], "in-fake to in and in-not (read), pins 2-9")
_parport_spec("sim_parport-in2", [], _PP_IN[8:], "in-fake to in and in-not (read), pins 10-15")


def _orient_rows(rng: random.Random) -> list[Row]:
    """Columns enable, mode, angle, position, tolerance: rising edges in each
    mode at positions around the target (ties at half a turn, negative
    positions, big and negative angles, NaN and infinities), settling with
    poserr in and out of tolerance, then random segments."""
    rows: list[Row] = []

    def seg(en: int, mode: int, ang: float, pos: list[float], tol: float = 0.5) -> None:
        rows.extend([float(en), float(mode), ang, p, tol] for p in pos)

    for mode, ang, pos in [
        (0, 90, 0.1), (0, 90, 2.7), (0, 300, 2.1), (1, 90, 2.1), (1, 90, 2.7),
        (2, 90, 2.1), (2, 90, 2.7), (0, 90, -2.7), (1, 90, -2.7), (2, 90, -2.7),
        (3, 90, 2.7), (-1, 90, 2.0), (0, 90, 2.25), (1, 90, 2.25), (2, 90, 2.25),
        (0, 90, 2.75), (0, 180, 2.0), (0, -90, 2.0), (0, 720, 2.0), (1, 720, 2.0),
        (1, -450, 2.0), (2, 720, 2.0), (2, -450, 2.0), (0, 3600, 2.0), (0, -3600, 2.0),
        (1, 360, 2.0), (2, 360, 2.0), (0, 90, INF), (0, 90, -INF), (0, INF, 2.0),
        (0, NAN, 2.0), (0, 90, NAN), (1, 100, 1e16), (0, 10, -0.0),
    ]:  # fmt: skip
        seg(0, mode, ang, [pos])
        seg(1, mode, ang, [pos, pos + 0.01])
    seg(1, 0, 180, [2.0])  # the angle is read at the rising edge only
    seg(0, 0, 90, [0.2])
    seg(1, 0, 90, [0.2] * 3 + [0.25] * 103 + [0.26] * 3 + [0.25] * 3)  # settle, latch
    seg(0, 0, 90, [0.25] * 2)
    seg(1, 0, 90, [0.25] * 50 + [0.3] * 10 + [0.25] * 55)  # time out of tolerance
    seg(0, 0, 90, [0.2])
    seg(1, 0, 90, [0.2] * 105)  # poserr -18: never within 0.5
    seg(0, 0, 90, [0.2])
    seg(1, 0, 90, [0.25 + 0.5 / 360] * 103)  # just below the tolerance
    seg(0, 0, 90, [0.2])
    seg(1, 0, 90, [0.25 - 0.4 / 360] * 103, 0.4)  # just beyond it
    for _ in range(12):
        mode, ang = rng.choice([0, 0, 1, 2]), round(rng.uniform(-400, 400), 3)
        p0 = round(rng.uniform(-5, 5), 4)
        seg(0, mode, ang, [p0])
        seg(1, mode, ang, [round(p0 + rng.uniform(-0.6, 0.6), 4) for _ in range(4)], 20.0)
    return rows


spec(
    Spec(
        "orient",
        [("enable", "b"), ("mode", "s"), ("angle", "f"), ("position", "f"), ("tolerance", "f")],
        [("command", "f"), ("poserr", "f"), ("is-oriented", "b")],
        _orient_rows,
        note="command at enable's rising edge by mode, poserr, is-oriented after 100 periods",
    )
)

_KB_CODES = [0, 1, 6, 7, 8, 9, 15, 20, 27, 36, 43, 48, 55, 56, 62, 63]


def _kb_rows(rng: random.Random) -> list[Row]:
    """Each key alone (press, hold, release), keys pressed and released
    together (one event a period, in scan order), random patterns."""
    n = len(_KB_CODES)
    rows: list[Row] = [[0.0] * n]
    for k in range(n):
        rows += [[float(i == k) for i in range(n)]] * 3 + [[0.0] * n] * 2
    for group in ([0, 1], [3, 4], [0, 15], [5, 9, 12], list(range(n))):
        on = [float(i in group) for i in range(n)]
        rows += [on] * (len(group) + 2) + [[0.0] * n] * (len(group) + 2)
    for _ in range(40):
        rows.append([float(rng.random() < 0.2) for _ in range(n)])
    return rows + [[0.0] * n] * (n + 2)


spec(
    Spec(
        "sim_matrix_kb",
        [(f"button.c{c % 8:02d}.r{c // 8:02d}", "b") for c in _KB_CODES],
        [("out", "u")],
        _kb_rows,
        setps=[{}, {}],
        note="keycodes: press, release, held and idle, one event a period in scan order",
    )
)

_SAH_X = ["homesw-out", "maxsw-out", "minsw-out", "bothsw-out"]
_SAH_X += ["maxsw-homesw-out", "minsw-homesw-out", "bothsw-homesw-out"]
_SAH_ALL = ["homesw-all", "limitsw-all", "limitsw-homesw-all"]


def _sah_rows(rng: random.Random) -> list[Row]:
    """Columns Xcurrent-pos, Xhoming, Ycurrent-pos, Yhoming: X through every
    switch edge of both instances (fine steps at the edges) with no axis, X,
    Y and both homing; NaN and infinities; random positions."""
    pts: list[float] = []
    for c in (4.0, 5.0, -4.0, -5.0, 1.0):
        pts += [round(c + i * 0.002, 4) for i in range(-8, 9)]
    for c in (2.0, 3.0, -2.0, -3.0, 0.3, 2.5):
        pts += [round(c + i * 0.05, 4) for i in range(-6, 7)]
    pts += [NAN, INF, -INF, 0.4, 0.2, 1.0125, 0.9875]
    rows: list[Row] = []
    for xh, yh in ((0, 0), (1, 0), (0, 1), (1, 1)):
        rows += [[p, float(xh), 1.5 if yh else 0.5, float(yh)] for p in pts]
    rows += [[round(rng.uniform(-6, 6), 3), float(rng.random() < 0.3), 0.5, 0.0] for _ in range(40)]
    return rows


spec(
    Spec(
        "sim_axis_hardware",
        [("Xcurrent-pos", "f"), ("Xhoming", "b"), ("Ycurrent-pos", "f"), ("Yhoming", "b")],
        [(f"X{o}", "b") for o in _SAH_X] + [(o, "b") for o in _SAH_ALL],
        _sah_rows,
        setps=[
            {
                "Xmaxsw-lower": "4",
                "Xmaxsw-upper": "5",
                "Xminsw-lower": "-5",
                "Xminsw-upper": "-4",
            },
            {
                "Xhomesw-pos": "0.3",
                "Xhomesw-hyst": "0.2",
                "Xmaxsw-lower": "2",
                "Xmaxsw-upper": "3",
                "Xminsw-lower": "-3",
                "Xminsw-upper": "-2",
                "limit-offset": "0.5",
                "Yhomesw-pos": "0.5",
                "Yhomesw-hyst": "0.2",
                "Ymaxsw-lower": "1",
                "Ymaxsw-upper": "2",
            },
        ],
        functs=["update"],
        note="X's switches at their edges, homing of X and of another axis, the -all outputs",
    )
)

_SAH_AXES = ["X", "X2", "Y", "Y2", "Z", "A", "U", "V"]


def _sah_axes_rows(rng: random.Random) -> list[Row]:
    return [[round(-9.0 + i * 0.125, 4)] for i in range(145)] + [[NAN]]


spec(
    Spec(
        "sim_axis_hardware",
        [(f"{a}current-pos", "f") for a in _SAH_AXES],
        [(f"{a}bothsw-homesw-out", "b") for a in _SAH_AXES]
        + [(f"{a}maxsw-out", "b") for a in _SAH_AXES]
        + [(o, "b") for o in _SAH_ALL],
        lambda rng: [r * len(_SAH_AXES) for r in _sah_axes_rows(rng)],
        setps=[
            {
                k: v
                for i, a in enumerate(_SAH_AXES)
                for k, v in (
                    (f"{a}homesw-pos", str(-8 + 2 * i)),
                    (f"{a}maxsw-lower", str(-7.5 + 2 * i)),
                    (f"{a}maxsw-upper", str(-7.5 + 2 * i + 0.5)),
                    (f"{a}minsw-lower", str(-6.5 + 2 * i)),
                    (f"{a}minsw-upper", str(-6.5 + 2 * i + 0.5)),
                )
            }
        ],
        functs=["update"],
        test="sim_axis_hardware-axes",
        note="every axis's pins at its own switch positions",
    )
)

_EPA_IN = [("active", "b"), ("is-on", "b"), ("enable-in", "b"), ("radius-ref", "f")]
_EPA_IN += [("angle", "f"), ("start-angle", "f"), ("fnum", "s"), ("rfraction", "f")]
_EPA_IN += [("fmult", "f"), ("k", "u")]
_EPA_OUT = [("is-off", "b"), ("enable-out", "b"), ("clear", "b"), ("kcounts", "s")]
_EPA_OUT += [("kreciprocal", "f"), ("eoffset-dbg", "f"), ("state-dbg", "u")]


def _epa_rows(rng: random.Random) -> list[Row]:
    """Columns active, is-on, enable-in, radius-ref, angle, start-angle, fnum,
    rfraction, fmult, k: machine off and on, enable with and without
    motion's eoffset-active, each function over angle sweeps (both ways,
    negative and big angles, start angles), stopping until eoffset-active
    drops, bad polygon sides and fnum, k 0, NaN and infinities, random rows."""
    rows: list[Row] = []

    def seg(act: int, on: int, en: int, r: float, angs: list[float], **kw: float) -> None:
        for a in angs:
            rows.append(
                [float(act), float(on), float(en), r, a, kw.get("sa", 0.0), kw.get("fn", 0.0)]
                + [kw.get("rf", 0.1), kw.get("fm", 6.0), kw.get("k", 10000.0)]
            )

    sweep = [float(a) for a in range(-30, 400, 7)]
    seg(0, 0, 0, 1.0, [0.0] * 3)
    seg(0, 0, 1, 1.0, [10.0] * 3)  # enabled while the machine is off
    seg(0, 1, 1, 1.0, [10.0] * 3)
    seg(0, 1, 0, 1.0, [10.0] * 3)
    seg(0, 1, 1, 1.0, [10.0] * 3)  # rising enable, eoffset not active yet
    for fn, fm in ((0, 6.0), (1, 6.0), (2, 6.0), (3, 6.0), (0, 3.0), (1, 4.0), (2, 2.5)):
        seg(1, 1, 1, 2.0, sweep, fn=fn, fm=fm, rf=0.2)
    seg(1, 1, 1, 2.0, sweep[::-3], fn=2, sa=45.0, rf=0.3)
    seg(1, 1, 1, 5.0, [-720.0, -365.0, 1e6, 3600.5, 1e-9], fn=0, sa=-30.0)
    seg(1, 1, 1, 5.0, [30.0, 31.0], fn=2, k=0.0)
    seg(1, 1, 1, 5.0, [30.0, 31.0], fn=2, k=1.0)
    seg(1, 1, 1, 5.0, [30.0, 31.0], fn=2, k=123456.0)
    seg(1, 1, 1, 1e6, [30.0, 31.0], fn=2, rf=1.0)  # beyond an s32
    seg(1, 1, 1, 5.0, [30.0, 31.0], fn=7)
    seg(1, 1, 1, 5.0, [30.0, 31.0], fn=-1)
    seg(1, 1, 1, 5.0, [30.0, NAN, INF, -INF, 32.0], fn=2)
    seg(1, 1, 1, NAN, [30.0, 31.0], fn=2)
    seg(1, 1, 1, 2.0, [30.0, 31.0], fn=2, rf=NAN)
    seg(1, 1, 0, 2.0, [40.0] * 3, fn=2)  # stopping: offset returns while active
    seg(0, 1, 0, 2.0, [40.0] * 3, fn=2)  # motion reports the offset gone
    seg(0, 1, 1, 2.0, [40.0] * 2, fn=2)
    seg(1, 1, 1, 2.0, [40.0, 41.0], fn=0, fm=2.0)  # a polygon of 2 sides
    seg(1, 1, 1, 2.0, [42.0, 43.0], fn=0, fm=6.0)  # corrected: no effect until re-enabled
    seg(1, 1, 0, 2.0, [43.0] * 2, fn=0)
    seg(0, 1, 0, 2.0, [43.0] * 2, fn=0)
    seg(0, 1, 1, 2.0, [43.0] * 2, fn=0)
    seg(1, 1, 1, 2.0, [44.0, 45.0], fn=1, fm=-3.0)
    seg(1, 1, 1, 2.0, [44.0, 45.0], fn=2, fm=0.0)
    seg(1, 0, 1, 2.0, [46.0] * 3, fn=2)  # machine turned off while running
    seg(0, 0, 1, 2.0, [46.0] * 2, fn=2)
    seg(0, 1, 1, 2.0, [46.0] * 2, fn=2)
    seg(1, 1, 1, 2.0, [46.0] * 2, fn=2)
    for _ in range(40):
        seg(
            int(rng.random() < 0.8), int(rng.random() < 0.9), int(rng.random() < 0.8),
            round(rng.uniform(0, 10), 3), [round(rng.uniform(-400, 400), 3)],
            sa=round(rng.uniform(-90, 90), 2), fn=float(rng.randrange(4)),
            rf=round(rng.uniform(0, 0.5), 3), fm=float(rng.randrange(3, 9)),
        )  # fmt: skip
    return rows


spec(
    Spec(
        "eoffset_per_angle",
        _EPA_IN,
        _EPA_OUT,
        _epa_rows,
        setps=[{}],
        prefix="eoffset-per-angle",
        note="offset by function and angle through the enable/active/is-on states",
    )
)


def _epa_state_rows(rng: random.Random) -> list[Row]:
    """The state machine and edge values: polygons of 2.5, just over 2 and
    7.5 sides, bad sides (<= 2) and NaN or infinite fmult per function,
    stopping (enable-in low, machine off), what a bad polygon needs before
    the next start (enable-in toggled), the square wave's edges, k 0, 3
    and 2^32-1, infinities and NaN in the other inputs, angles on the
    sides' edges (negative ones fold differently)."""
    rows: list[Row] = []

    def r(
        act: int, on: int, en: int, rad: float, a: float, fn: int, fm: float, **kw: float
    ) -> None:
        rows.append(
            [float(act), float(on), float(en), rad, a, kw.get("sa", 0.0), float(fn)]
            + [kw.get("rf", 0.2), fm, kw.get("k", 10000.0)]
        )

    def stop_start(fn: int) -> None:
        r(0, 1, 0, 2, 20, fn, 6)
        r(0, 1, 0, 2, 20, fn, 6)
        r(0, 1, 0, 2, 20, fn, 6)
        r(0, 1, 1, 2, 20, 2, 6)
        r(0, 1, 1, 2, 20, 2, 6)

    r(0, 1, 0, 1, 0, 0, 6, rf=0.1)
    r(0, 1, 1, 1, 0, 0, 6, rf=0.1)
    for fm in (2.5, 2.0001, 3.0, 7.5):
        r(1, 1, 1, 2, 20, 1, fm)
        r(1, 1, 1, 2, -50, 1, fm)
    for a in (-70, -10, 50, -130, -100, -40, -31, -29, 31, 29, 89, 91, -89, -91, -149, -151):
        r(1, 1, 1, 2, a, 0, 6)
    r(1, 1, 1, 2, -37.911, 0, 6, sa=32.1)
    r(1, 1, 1, 2, 0, 0, 6, sa=70)
    for a in (-60, -45.1, -45, -44.9, -15.1, -15, -14.9, 0, 14.9, 15, 45, 45.1, 75, 90):
        r(1, 1, 1, 2, a, 3, 6)
    for fn, fm in ((1, 2.0), (2, 0.0), (2, -1.0), (3, 0.0), (3, -1.0), (0, NAN), (1, NAN)):
        r(1, 1, 1, 2, 20, fn, fm)
        r(1, 1, 1, 2, 20, fn, fm)
        stop_start(fn)
    for fn, fm in ((2, NAN), (3, NAN), (0, -3.0), (1, INF), (0, INF), (2, 1e-300), (2, 1e9)):
        r(1, 1, 1, 2, 20, fn, fm)
        r(1, 1, 1, 2, 20, fn, fm)
        stop_start(fn)
    r(1, 1, 1, 2, 20, 0, 1.0)  # a bad polygon, then the machine off and on
    r(1, 1, 1, 2, 20, 0, 6)
    r(1, 0, 1, 2, 20, 0, 6)
    r(1, 1, 0, 2, 20, 0, 6)
    r(1, 1, 0, 2, 20, 0, 6)
    r(1, 1, 1, 2, 20, 2, 6)
    r(1, 1, 1, 2, 20, 2, 6)
    r(1, 1, 0, 2, 20, 2, 6)  # stop; enable back while stopping
    r(1, 1, 1, 2, 20, 2, 6)
    r(0, 1, 1, 2, 20, 2, 6)
    r(0, 1, 1, 2, 20, 2, 6)
    r(0, 1, 1, 2, 20, 2, 6)
    r(0, 1, 0, 2, 20, 2, 6)  # stop, machine off while stopping
    r(0, 0, 0, 2, 20, 2, 6)
    r(0, 1, 0, 2, 20, 2, 6)
    r(0, 1, 1, 2, 20, 2, 6)
    r(0, 1, 1, 2, 20, 2, 6)
    for a in (0.0, 7.5, 15.0, 22.5, 37.5, 52.5, 1e-7, 59.9999999, 390.0, 285.0, 110.0):
        for fn in (2, 3, 1, 0):
            r(0, 1, 1, 3, a, fn, 6, rf=0.3)
    for k in (0.0, 4294967295.0, 3.0, 2147483648.0, 1.0):
        r(0, 1, 1, 3, 20, 2, 6, rf=0.3, k=k)
    r(0, 1, 1, 3, 20, 2, 6, rf=INF)
    r(0, 1, 1, -2, 20, 0, 6)
    r(0, 1, 1, 0, 20, 0, 6)
    r(0, 1, 1, INF, 20, 0, 6)
    r(0, 1, 1, 3, 20, 0, 6, rf=-0.2)
    r(0, 1, 1, 3, 20, 2, 6, sa=NAN)
    for a in (1.3e11 + 20, 1e15 + 20, -1e12 - 20):  # beyond an int's count of sides
        r(0, 1, 1, 3, a, 0, 6)
        r(0, 1, 1, 3, a, 1, 6)
    r(0, 1, 1, 3, -1e20, 2, 6)
    r(0, 1, 1, 3, 20, 2, 6)
    return rows


spec(
    Spec(
        "eoffset_per_angle",
        _EPA_IN,
        _EPA_OUT,
        _epa_state_rows,
        setps=[{}],
        prefix="eoffset-per-angle",
        test="eoffset_per_angle-states",
        note="states, bad polygons, edges of the sides and of the square wave, odd k",
    )
)
