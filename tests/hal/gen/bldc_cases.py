# SPDX-License-Identifier: GPL-2.0-or-later
"""Dev tool (never run by `make test`): write the tests/hal/bldc-* folders.

Each folder streams inputs into bldc instances (and, for the encoder modes,
quadrature into an encoder whose rawcounts and index-enable go to bldc)
and samples the outputs every period; float outputs are scaled by 2^40
(exact) so the sampler's 6 decimals compare them bit for bit.  `expected`
is recorded from LinuxCNC 2.9 with record_linuxcnc.sh.

    python3 tests/hal/gen/bldc_cases.py [FOLDER...]
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

HERE = Path(__file__).resolve().parent
GAIN = 1099511627776.0
NAN = float("nan")
INF = float("inf")

Row = list[float]
Out = tuple[str, str]  # (pin, type f/b/s/u)

# Hall codes (H1 H2 H3) of the excitations B-A, C-A, C-B, A-B, A-C, B-C
PAT25 = ["101", "100", "110", "010", "011", "001"]

F3: list[Out] = [("A-value", "f"), ("B-value", "f"), ("C-value", "f")]
B3: list[Out] = [("A-on", "b"), ("B-on", "b"), ("C-on", "b")]
F6: list[Out] = [(f"{p}-{s}", "f") for p in "ABC" for s in ("high", "low")]
B6: list[Out] = [(f"{p}-{s}-on", "b") for p in "ABC" for s in ("high", "low")]
HO: list[Out] = [("hall1-out", "b"), ("hall2-out", "b"), ("hall3-out", "b")]
FO: list[Out] = [("C1-out", "b"), ("C2-out", "b"), ("C4-out", "b"), ("C8-out", "b")]
PH: list[Out] = [("phase-angle", "f")]
PR: list[Out] = [("phase-angle", "f"), ("rotor-angle", "f")]


def personality(cfg: str) -> int:
    bits = {"h": 1, "a": 2, "q": 4, "i": 8, "f": 16, "B": 0x100, "6": 0x200, "H": 0x400}
    bits |= {"F": 0x800, "T": 0x1000}
    p = 0
    for c in cfg:
        p |= bits.get(c, 0)
    return p


def pin_exists(pin: str, cfg: str) -> bool:
    """The input pins of an instance, per man 9 bldc."""
    p = personality(cfg)
    base = pin.rstrip("0123456789") if pin.startswith("hall") else pin
    cond = {
        "hall": p & 1,
        "C1": p & 0x10,
        "C2": p & 0x10,
        "C4": p & 0x10,
        "C8": p & 0x10,
        "lead-angle": p & 6,
        "frequency": (p & 15) == 0,
        "initvalue": p & 4,
        "rawcounts": p & 6,
        "index-enable": p & 8,
        "init": (p & 5) == 4,
    }
    return bool(cond.get(base, True))


@dataclass
class Inst:
    cfg: str
    outs: list[Out]
    setps: dict[str, str] = field(default_factory=dict)


@dataclass
class Case:
    """One test folder.  inputs: (name, type, targets); a name `enc.PIN`
    goes to the encoder, `bldc.PIN` to every instance that has the pin,
    `K.PIN` (K an instance number) to instance K only."""

    note: str
    insts: list[Inst]
    inputs: list[tuple[str, str]]
    rows: Callable[[], list[Row]]
    period: int = 1000000
    encoder: bool = False
    tail: list[str] = field(default_factory=list)


def fmt(x: float, t: str) -> str:
    if t in "su":
        return str(int(x))
    if t == "b":
        return "1" if x else "0"
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return repr(float(x))


def write(name: str, c: Case) -> None:
    rows = c.rows()
    d = HERE.parent / name
    d.mkdir(exist_ok=True)
    outs = [(f"bldc.{k}.{p}", t) for k, i in enumerate(c.insts) for p, t in i.outs]
    if c.encoder:
        outs += [("encoder.0.rawcounts", "s"), ("encoder.0.index-enable", "b")]
    assert len(outs) <= 20, name
    chunks = [c.inputs[i : i + 20] for i in range(0, len(c.inputs), 20)]
    cfg = ",".join(i.cfg for i in c.insts)
    hal = [
        f"# bldc: {c.note}",
        "# Float outputs are scaled by 2^40 (exact) before the sampler, so its",
        "# 6 decimals compare them bit for bit (written by tests/hal/gen/bldc_cases.py).",
        f"loadrt bldc cfg={cfg}",
    ]
    if c.encoder:
        hal.append("loadrt encoder num_chan=1")
    hal += [
        f"loadrt threads name1=t period1={c.period}",
        f"loadrt streamer depth="
        + ",".join([str(len(rows) + 8)] * len(chunks))
        + " cfg="
        + ",".join("".join(t for _, t in ch) for ch in chunks),
        f"loadrt sampler depth={len(rows) + 8} cfg={''.join(t for _, t in outs)}",
    ]
    nfloat = sum(1 for _, t in outs if t == "f")
    if nfloat:
        hal.append(f"loadrt scale count={nfloat}")
    for s in range(len(chunks)):
        hal.append(f"addf streamer.{s} t")
    if c.encoder:
        hal += ["addf encoder.update-counters t", "addf encoder.capture-position t"]
    j = 0
    for s, ch in enumerate(chunks):
        for k, (pin, _) in enumerate(ch):
            scope, _, pname = pin.partition(".")
            if scope == "enc":
                targets = [f"encoder.0.{pname}"]
            elif scope == "bldc":
                targets = [
                    f"bldc.{n}.{pname}" for n, i in enumerate(c.insts) if pin_exists(pname, i.cfg)
                ]
            else:
                targets = [f"bldc.{scope}.{pname}"]
            hal.append(f"net i{j} streamer.{s}.pin.{k}" + (" => " + " ".join(targets)))
            j += 1
    if c.encoder:
        raw = [
            f"bldc.{n}.rawcounts" for n, i in enumerate(c.insts) if pin_exists("rawcounts", i.cfg)
        ]
        ie = [
            f"bldc.{n}.index-enable"
            for n, i in enumerate(c.insts)
            if pin_exists("index-enable", i.cfg)
        ]
        hal.append("net raw encoder.0.rawcounts" + (" => " + " ".join(raw) if raw else ""))
        hal.append("net ie encoder.0.index-enable " + " ".join(ie))
    for n, i in enumerate(c.insts):
        for p, v in i.setps.items():
            hal.append(f"setp bldc.{n}.{p} {v}")
        hal.append(f"addf bldc.{n} t")
    s = 0
    for k, (pin, t) in enumerate(outs):
        if pin == "encoder.0.rawcounts":
            hal.append(f"net raw => sampler.0.pin.{k}")
        elif pin == "encoder.0.index-enable":
            hal.append(f"net ie => sampler.0.pin.{k}")
        elif t == "f":
            hal += [
                f"net o{k} {pin} => scale.{s}.in",
                f"net so{k} scale.{s}.out => sampler.0.pin.{k}",
                f"setp scale.{s}.gain {GAIN!r}",
                f"addf scale.{s} t",
            ]
            s += 1
        else:
            hal.append(f"net o{k} {pin} => sampler.0.pin.{k}")
    hal += ["addf sampler.0 t"]
    hal += [f"loadusr -w halstreamer -c {s} in{s}.txt" for s in range(len(chunks))]
    hal += ["start", f"loadusr -w halsampler -n {len(rows)}", "stop"] + c.tail
    (d / "test.hal").write_text("\n".join(hal) + "\n")
    col = 0
    for s, ch in enumerate(chunks):
        with open(d / f"in{s}.txt", "w") as f:
            for r in rows:
                f.write(" ".join(fmt(x, t) for x, (_, t) in zip(r[col : col + len(ch)], ch)))
                f.write("\n")
        col += len(ch)
    (d / "README").write_text(
        "expected: LinuxCNC 2.9\n\n"
        "`expected` is the output of LinuxCNC 2.9's `halrun -f test.hal` in this\n"
        "folder, recorded with tests/hal/gen/record_linuxcnc.sh (normalized by\n"
        "../halnorm.py); our halrun must reproduce it byte for byte (the\n"
        "functions' tmax parameters are left out of the listings).  test.hal and\n"
        "in*.txt are written by tests/hal/gen/bldc_cases.py: streamer -> (encoder\n"
        "->) bldc -> (scale x 2^40, exact) -> sampler in one thread, every period\n"
        "sampled, so the output does not depend on timing.\n"
    )


def quad(n: int) -> tuple[int, int]:
    return [(0, 0), (1, 0), (1, 1), (0, 1)][n % 4]


def hall_bits(k: int) -> list[int]:
    return [int(b) for b in PAT25[k % 6]]


def motor(n: int, cpr: int = 256) -> list[int]:
    """Hall (pattern 25) and Fanuc code of a motor at count n."""
    th = (n % cpr) / cpr
    k = math.ceil(th * 6 - 0.5) % 6
    g = math.floor(th * 16)
    g ^= g >> 1
    return hall_bits(k) + [g & 1, (g >> 1) & 1, (g >> 2) & 1, (g >> 3) & 1]


# ---------------------------------------------------------------- cases

CASES: dict[str, Case] = {}

IN_N = [("bldc.value", "f"), ("bldc.frequency", "f"), ("bldc.rev", "b")]


def _n_rows() -> list[Row]:
    rows: list[Row] = []
    for i in range(560):
        v = 0.8 if i < 300 else (-0.6 if i < 450 else 0.0)
        rows.append([v, 3.0 if i < 520 else -7.0, 1 if 400 <= i < 430 else 0])
    rows += [[1.0, 10.0, 0]] * 30 + [[0.5, 250.0, 0]] * 6 + [[0.5, 0.37, 1]] * 6
    rows += [[NAN, 1.0, 0]] * 3 + [[INF, 1.0, 0]] * 2 + [[-INF, 1.0, 1]] * 2
    return rows


CASES["bldc-n"] = Case(
    "no feedback (n): the field turns at frequency; sinusoidal, forced trapezoidal (T), "
    "3 bits (B), Hall (H) and Fanuc (F) outputs, value and rev",
    [
        Inst("nT", F3 + PH),
        Inst("nB", B3),
        Inst("n", F3 + [("out", "f")]),
        Inst("nH", HO),
        Inst("nF", FO),
    ],
    IN_N,
    _n_rows,
)

CASES["bldc-n6"] = Case(
    "no feedback: six outputs, floats (6), bits (B6), trapezoidal floats (T6)",
    [Inst("n6", F6), Inst("nB6", B6), Inst("nT6", F6[:4] + [("out-dir", "b")])],
    IN_N,
    _n_rows,
    period=250000,
)

IN_A = [("bldc.value", "f"), ("bldc.rev", "b"), ("bldc.rawcounts", "s"), ("bldc.lead-angle", "f")]
O8: list[Out] = F3 + [("out", "f"), ("out-abs", "f"), ("out-dir", "b")] + PR


def _a_rows() -> list[Row]:
    r = random.Random(5)
    rows: list[Row] = []
    for i in range(140):
        raw = i * 7 - 200 + (r.randint(-3, 3) if i > 60 else 0)
        v = [1.0, -1.0, 0.5, 0.0][(i // 15) % 4]
        lead = [90.0, 0.0, 45.0, -30.0, 400.0, 90.0][(i // 20) % 6]
        rows.append([v, 1 if (i // 40) % 2 else 0, raw, lead])
    raw = 100
    for i in range(60):  # fast and reversing: the half-period extrapolation
        raw += [3, 40, -57, 0, 1, -1, 200][i % 7]
        rows.append([0.7, 0, raw, 90.0])
    return rows


CASES["bldc-a"] = Case(
    "absolute encoder (a): rotor from the counts (half the last step added), lead, "
    "value/rev direction, poles/scale/encoder-offset",
    [Inst("a", O8), Inst("a", O8, {"encoder-offset": "10", "scale": "1000", "poles": "6"})],
    IN_A,
    _a_rows,
)


def _a_out_rows() -> list[Row]:
    rows: list[Row] = []
    for lead in (0.0, 90.0, 45.0):
        for v in (0.7, -0.7):
            for raw in range(0, 260, 2):
                rows.append([v, 0, raw, lead])
    raw = 0
    for i in range(120):
        raw += 3 if i < 60 else -2
        rows.append([0.7 if (i // 25) % 2 == 0 else -0.4, 1 if 30 <= i < 45 else 0, raw, 90.0])
    return rows


CASES["bldc-a-outputs"] = Case(
    "absolute encoder: trapezoidal (T) and 3-bit (B) drive from the rotor sector, Hall (H) "
    "and Fanuc (F) emulation, sector boundaries",
    [Inst("aT", F3 + PR), Inst("aB", B3), Inst("aH", HO), Inst("aF", FO), Inst("a6", F6[:4])],
    IN_A,
    _a_out_rows,
)


def _a_edge_rows() -> list[Row]:
    vals = [0.7, -0.7, NAN, INF, -INF, 0.0, -0.0, 1e300]
    leads = [90.0, NAN, INF, -720.0, 1e6]
    rows: list[Row] = []
    raw = 0
    for i in range(80):
        raw += [3, -2, 7, 0, -11][i % 5]
        rows.append([vals[i % len(vals)], (i // 20) % 2, raw, leads[(i // 16) % len(leads)]])
    return rows


OX: list[Out] = [
    ("A-value", "f"),
    ("out", "f"),
    ("out-dir", "b"),
    ("phase-angle", "f"),
    ("rotor-angle", "f"),
]
CASES["bldc-a-edge"] = Case(
    "absolute encoder: NaN/inf value and lead-angle, odd poles, scale 0, negative "
    "scale/poles, and a disabled instance (a with q)",
    [
        Inst("aq", [("A-value", "f"), ("out", "f"), ("out-abs", "f"), ("out-dir", "b")]),
        Inst("a", OX[:1] + OX[3:], {"poles": "5", "scale": "500"}),
        Inst("a", OX[:1] + OX[3:], {"scale": "0"}),
        Inst("a", OX, {"scale": "-512", "poles": "-4", "encoder-offset": "-7"}),
        Inst("a", OX[:1] + OX[4:], {"poles": "0"}),
    ],
    IN_A,
    _a_edge_rows,
)

IN_H = [
    ("bldc.value", "f"),
    ("bldc.rev", "b"),
    ("bldc.hall1", "b"),
    ("bldc.hall2", "b"),
    ("bldc.hall3", "b"),
]
OH: list[Out] = F3 + [("hall-error", "b")] + PR


def _h_rows() -> list[Row]:
    rows: list[Row] = []
    for v, rev in ((1.0, 0), (-1.0, 0), (0.5, 1)):
        for code in range(8):
            rows.append([v, rev, code & 1, (code >> 1) & 1, (code >> 2) & 1])
        for code in [1, 3, 2, 6, 4, 5, 1, 3, 2, 6, 4, 5]:
            rows.append([v, rev, code & 1, (code >> 1) & 1, (code >> 2) & 1])
    return rows


CASES["bldc-h"] = Case(
    "Hall sensors (h): trapezoidal drive per pattern (25, 0, 17), rotor/phase angles, "
    "hall-error on invalid codes",
    [Inst("h", OH), Inst("h", OH, {"pattern": "0"}), Inst("h", OH, {"pattern": "17"})],
    IN_H,
    _h_rows,
)


def _h_err_rows() -> list[Row]:
    """Per instance its own Hall sequence: adjacent steps, repeats, a skip, an
    invalid code, the first period."""
    seqs = [
        [2, 2, 3, 4, 3, 2, 1, 0, 5, 4, 2, 3, 4, 5, 0, 3, 4],
        [0, 1, 2, 3, 4, 5, 0, 1, 0, 5, 4, 3, 3, 3, -1, 3, 4],
        [-1, -1, -1, 0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 5, 0, 1],
        [3, 0, 0, 0, 1, 2, 3, 4, 5, -2, 0, 1, 2, 3, 4, 5, 0],
    ]
    rows: list[Row] = []
    for i in range(len(seqs[0])):
        r: Row = [1.0, 0]
        for s in seqs:
            k = s[i]
            r += [0, 0, 0] if k == -1 else [1, 1, 1] if k == -2 else hall_bits(k)
        rows.append(r)
    return rows


CASES["bldc-h-error"] = Case(
    "Hall sensors: when hall-error is set (skipped state, invalid code; not in the first "
    "periods) and that it stays set",
    [Inst("h", [("hall-error", "b"), ("rotor-angle", "f")]) for _ in range(4)],
    [("bldc.value", "f"), ("bldc.rev", "b")]
    + [(f"{k}.hall{j}", "b") for k in range(4) for j in (1, 2, 3)],
    _h_err_rows,
)


def _h_out_rows() -> list[Row]:
    rows: list[Row] = []
    seq = [0, 1, 2, 3, 4, 5, 0, 1, 2, 2, 1, 0, 5, 4, 3]
    for v in (0.8, -0.5, 0.0):
        for k in seq:
            rows.append([v, 0] + hall_bits(k))
    rows += [[0.8, 0, 0, 0, 0], [0.8, 0, 1, 1, 1], [0.8, 0] + hall_bits(2)]
    return rows


CASES["bldc-h-outputs"] = Case(
    "Hall sensors: Hall translation (H, output-pattern), Fanuc emulation (F), 3 bits (B), "
    "6 bits (B6), invalid codes",
    [
        Inst("hH", HO),
        Inst("hF", FO),
        Inst("hB", B3),
        Inst("hB6", B6),
        Inst("hH", HO, {"output-pattern": "17"}),
    ],
    IN_H,
    _h_out_rows,
)

IN_Q = [
    ("bldc.value", "f"),
    ("bldc.rev", "b"),
    ("bldc.init", "b"),
    ("bldc.initvalue", "f"),
    ("bldc.lead-angle", "f"),
    ("enc.phase-A", "b"),
    ("enc.phase-B", "b"),
    ("enc.phase-Z", "b"),
]


def _enc_rows(segments: list[tuple]) -> Callable[[], list[Row]]:
    def rows() -> list[Row]:
        out: list[Row] = []
        n = 0
        for k, v, rev, init, iv, dn, z_at in segments:
            for _ in range(k):
                n += dn
                a, b = quad(n)
                z = 1 if (z_at is not None and n % 400 == z_at) else 0
                out.append([v, rev, init, iv, 90.0, a, b, z])
        return out

    return rows


OQ: list[Out] = [("A-value", "f"), ("init-done", "b"), ("out", "f")] + PR
CASES["bldc-align"] = Case(
    "incremental encoder (q): magnetic alignment (current ramp, -90/+90/0 degree sweep, hold), "
    "paused while init is low, drive-offset, alignment again; (qi) index alignment turning "
    "the field until the index",
    [Inst("q", OQ), Inst("q", OQ, {"drive-offset": "30"}), Inst("qi", OQ)],
    IN_Q,
    _enc_rows(
        [
            (3, 1.0, 0, 0, 0.25, 0, None),
            (125, 1.0, 0, 1, 0.25, 0, None),
            (10, 1.0, 0, 0, 0.25, 0, None),
            (650, 1.0, 1, 1, 0.25, 0, None),
            (30, 1.0, 0, 1, 0.25, 1, 5000),
            (10, 1.0, 0, 0, 0.25, 1, 5000),
            (100, 1.0, 0, 1, 0.25, 1, 5000),
        ]
    ),
    period=4000000,
    encoder=True,
    tail=["show param bldc.*.offset-measured", "show param bldc.*.in-type"],
)

CASES["bldc-index"] = Case(
    "incremental encoder with index (qi): index passed before init, init edges, the field "
    "turning until the encoder clears index-enable, encoder-offset, alignment again",
    [Inst("qi", OQ), Inst("qi", OQ, {"encoder-offset": "-5"})],
    IN_Q,
    _enc_rows(
        [
            (3, 1.0, 0, 0, 0.2, 0, None),
            (30, 1.0, 0, 0, 0.2, 1, 10),
            (5, 1.0, 1, 1, 0.3, 0, None),
            (5, 1.0, 1, 0, 0.3, 0, None),
            (5, 1.0, 1, 1, 0.3, 0, None),
            (60, 1.0, 1, 1, 0.3, -1, 10),
            (10, 1.0, 0, 1, 0.2, 1, 10),
            (5, 1.0, 0, 0, 0.2, 1, 10),
            (5, 1.0, 0, 1, 0.2, 1, 10),
            (20, -0.5, 0, 1, 0.2, 1, 10),
        ]
    ),
    encoder=True,
    tail=["show param bldc.*.offset-measured", "show param bldc.*.in-type"],
)

IN_M = [
    ("bldc.value", "f"),
    ("bldc.rev", "b"),
    ("bldc.initvalue", "f"),
    ("bldc.lead-angle", "f"),
    ("bldc.hall1", "b"),
    ("bldc.hall2", "b"),
    ("bldc.hall3", "b"),
    ("bldc.C1", "b"),
    ("bldc.C2", "b"),
    ("bldc.C4", "b"),
    ("bldc.C8", "b"),
    ("enc.phase-A", "b"),
    ("enc.phase-B", "b"),
    ("enc.phase-Z", "b"),
]


def _motor_rows() -> list[Row]:
    rows: list[Row] = []
    n = 20
    segs = [
        (10, 1.0, 0, 0),
        (30, 1.0, 0, 1),
        (30, 1.0, 0, 1),
        (10, -0.7, 0, 1),
        (60, -0.7, 0, 1),
        (20, 0.4, 1, -1),
    ]
    for k, v, rev, dn in segs:
        for _ in range(k):
            n += dn
            a, b = quad(n - 20)
            z = 1 if (n - 20) % 400 == 80 else 0
            rows.append([v, rev, 0.2, 90.0] + motor(n) + [a, b, z])
    return rows


OM: list[Out] = F3 + PR
CASES["bldc-qh"] = Case(
    "Hall sensors and incremental encoder: trapezoidal until the first Hall edge (qh) or "
    "the index (qhi), then sinusoidal from the encoder",
    [
        Inst("qh", OM + [("hall-error", "b")]),
        Inst("qhi", OM + [("hall-error", "b")], {"encoder-offset": "7"}),
    ],
    IN_M,
    _motor_rows,
    encoder=True,
    tail=["show param bldc.*.offset-measured", "show param bldc.*.in-type"],
)

CASES["bldc-f"] = Case(
    "Fanuc Gray code (f): sinusoidal at the code's sector; with an incremental encoder "
    "until the first code edge (fq) or the index (fqi)",
    [Inst("f", OM), Inst("fq", OM), Inst("fqi", OM[:1] + PR)],
    IN_M,
    _motor_rows,
    encoder=True,
    tail=["show param bldc.*.offset-measured", "show param bldc.*.in-type"],
)


def _codes_rows() -> list[Row]:
    rows: list[Row] = []
    for g in list(range(16)) + [0]:
        rows += [[1.0, 0, g & 1, (g >> 1) & 1, (g >> 2) & 1, (g >> 3) & 1]] * 2
    rows += [[-1.0, 0, 1, 0, 0, 0]] * 2 + [[1.0, 1, 1, 0, 0, 0]] * 2
    return rows


CASES["bldc-f-codes"] = Case(
    "Fanuc Gray code: the angle of every code, direction, trapezoidal (fT), Hall " "emulation (fH)",
    [Inst("f", [("A-value", "f"), ("out", "f")] + PR), Inst("fT", F3 + PH), Inst("fH", HO)],
    [
        ("bldc.value", "f"),
        ("bldc.rev", "b"),
        ("bldc.C1", "b"),
        ("bldc.C2", "b"),
        ("bldc.C4", "b"),
        ("bldc.C8", "b"),
    ],
    _codes_rows,
)


def _edge_rows(direction: int) -> Callable[[], list[Row]]:
    """Six qh and two fq instances on one encoder, each with its own Hall or
    Fanuc signals (motor offsets), so each meets its first edge elsewhere."""

    def rows() -> list[Row]:
        out: list[Row] = []
        starts = [round(k * 256 / 6.0) for k in range(6)]
        fstarts = [200, 245] if direction > 0 else [100, 17]
        for i in range(60):
            n = i * direction if i >= 3 else 0
            a, b = quad(n)
            r: Row = [1.0, 0, 90.0, a, b, 0]
            for s in starts:
                r += motor(s + n)[:3]
            for s in fstarts:
                r += motor(s + n)[3:]
            out.append(r)
        return out

    return rows


IN_E = [
    ("bldc.value", "f"),
    ("bldc.rev", "b"),
    ("bldc.lead-angle", "f"),
    ("enc.phase-A", "b"),
    ("enc.phase-B", "b"),
    ("enc.phase-Z", "b"),
]
IN_E += [(f"{k}.hall{j}", "b") for k in range(6) for j in (1, 2, 3)]
IN_E += [(f"{k}.C{j}", "b") for k in (6, 7) for j in (1, 2, 4, 8)]
for _name, _dir in (("bldc-edges-fwd", 1), ("bldc-edges-back", -1)):
    CASES[_name] = Case(
        "the first Hall edge (qh) and Fanuc edge (fq) in every sector, "
        + ("forward" if _dir > 0 else "backward")
        + ": the edge angle and the measured offset",
        [Inst("qh", [("rotor-angle", "f")]) for _ in range(6)]
        + [Inst("fq", [("rotor-angle", "f")]) for _ in range(2)],
        IN_E,
        _edge_rows(_dir),
        encoder=True,
        tail=["show param bldc.*.offset-measured"],
    )


def main() -> None:
    import sys

    names = sys.argv[1:] or sorted(CASES)
    for name in names:
        write(name, CASES[name])


if __name__ == "__main__":
    main()
