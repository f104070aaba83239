# SPDX-License-Identifier: GPL-2.0-or-later
"""Dev tool (not run by `make test`): writes test.hal and the streamed input
files of the steptest-run and steptest-loop regression tests.  Their
`expected` files are LinuxCNC 2.9's output of the same test.hal (see each
README); rerun this only together with a new recording.

    python3 tests/hal/steptest-run/gen.py
"""

from __future__ import annotations

from pathlib import Path

HERE = Path(__file__).resolve().parent
INS = ["jog-minus", "jog-plus", "run", "dir", "pause", "maxvel", "amplitude", "position-fb"]
IN_TYPE = {"dir": "s", "pause": "s", "maxvel": "f", "amplitude": "f", "position-fb": "f"}
OUTS = ["position-cmd", "running", "run-target", "run-start", "run-low", "run-high"]
DEFAULT = {"jog-minus": 0, "jog-plus": 0, "run": 0, "dir": 0, "pause": 0, "maxvel": 10.0}
DEFAULT |= {"amplitude": 1.0, "position-fb": 0.0}
NAN = float("nan")


def rows(n: int, segs: list[tuple[int, int, str, float]]) -> list[list]:
    """n rows of the defaults, then each (from, to, input, value) applied."""
    out = [[DEFAULT[p] for p in INS] for _ in range(n)]
    for a, b, p, v in segs:
        for i in range(a, min(b, n)):
            out[i][INS.index(p)] = v
    return out


def fmt(p: str, v: float) -> str:
    if IN_TYPE.get(p) == "f":
        return repr(float(v))
    return str(int(v))


def write_test(
    name: str, comment: str, chans: list[list], n: int, period: int, eps: list[float]
) -> None:
    d = HERE.parent / name
    d.mkdir(exist_ok=True)
    hal = [f"# {line}".rstrip() for line in comment.strip().splitlines()]
    hal.append(f"loadrt threads name1=t period1={period}")
    hal.append(f"loadrt steptest count={len(chans)}")
    cfg = "".join(IN_TYPE.get(p, "b") for p in INS)
    ocfg = "".join("b" if p == "running" else "f" for p in OUTS)
    k = len(chans)
    hal.append(f"loadrt streamer depth={','.join([str(n + 4)] * k)} cfg={','.join([cfg] * k)}")
    hal.append(f"loadrt sampler depth={','.join([str(n + 4)] * k)} cfg={','.join([ocfg] * k)}")
    for c in range(k):
        for j, p in enumerate(INS):
            hal.append(f"net s{c}-{p} streamer.{c}.pin.{j} => steptest.{c}.{p}")
        for j, p in enumerate(OUTS):
            hal.append(f"net s{c}-{p} steptest.{c}.{p} => sampler.{c}.pin.{j}")
        if eps[c] != 0.001:
            hal.append(f"setp steptest.{c}.epsilon {eps[c]}")
    for c in range(k):
        hal.append(f"addf streamer.{c} t")
    hal += [f"addf steptest.{c} t" for c in range(k)]
    for c in range(k):
        hal.append(f"addf sampler.{c} t")
    for c, ch in enumerate(chans):
        text = "".join(" ".join(fmt(p, v) for p, v in zip(INS, r)) + "\n" for r in ch)
        (d / f"in{c}.txt").write_text(text)
        hal.append(f"loadusr -w halstreamer -c {c} in{c}.txt")
    hal.append("start")
    for c in range(k):
        hal.append(f"loadusr -w halsampler -c {c} -n {n}")
    hal.append("stop")
    # every channel ends idle or moving: elapsed no longer changes
    hal += [f"getp steptest.{c}.elapsed" for c in range(k)]
    (d / "test.hal").write_text("\n".join(hal) + "\n")


def run_test() -> None:
    n = 1300
    chans = [
        # pause 0: an end counts when position-fb is within epsilon of it
        # (strictly); the other end is commanded the period after, or at
        # once when position-fb comes back to an end it had left
        rows(
            n,
            [(5, 90, "run", 1), (20, 40, "position-fb", -1.0), (40, 41, "position-fb", 1.0)]
            + [(41, 60, "position-fb", -1.0), (60, 62, "position-fb", 1.0)]
            + [(100, 200, "run", 1), (110, 120, "position-fb", -0.998)]
            + [(120, 130, "position-fb", -0.9995), (130, 140, "position-fb", 0.9991)]
            + [(140, 150, "position-fb", 0.999), (150, 160, "position-fb", -1.0009)]
            + [(160, 170, "position-fb", -1.00099), (210, 260, "run", 1), (210, 260, "dir", 1)]
            + [(220, 230, "position-fb", 1.0), (240, 245, "position-fb", 1.0)]
            + [(270, 330, "run", 1), (270, 330, "dir", 2), (280, 290, "position-fb", -1.0)]
            + [(340, 400, "run", 1), (340, 400, "dir", 3), (350, 360, "position-fb", -1.0)]
            + [(410, 470, "run", 1), (410, 470, "amplitude", -0.5)]
            + [(420, 430, "position-fb", -0.5), (480, 520, "run", 1), (480, 520, "amplitude", 0.0)]
            + [(530, 560, "run", 1), (530, 600, "amplitude", 0.001)],
        ),
        # run released while away from the start: the start is commanded
        # until position-fb is back with run still released; run pressed
        # again meanwhile changes nothing
        rows(
            n,
            [(5, 10, "run", 1), (12, 60, "run", 1), (6, 20, "position-fb", -1.0)]
            + [(60, 70, "position-fb", 0.3), (100, 130, "run", 1), (100, 130, "jog-plus", 1)]
            + [
                (100, 140, "position-fb", 0.7),
                (150, 160, "run", 1),
                (150, 200, "position-fb", -1.0),
            ]
            + [(170, 180, "jog-minus", 1), (200, 210, "position-fb", 0.0)]
            + [(1200, n, "run", 1), (1205, n, "position-fb", -1.0)],
        ),
        # idle: jogs (minus first), a negative and a tiny maxvel; position-cmd
        # follows position-fb only when they differ by more than 1e-5; NaN
        # position-fb, then a run started on it never ends
        rows(
            n,
            [(5, 10, "jog-plus", 1), (15, 20, "jog-minus", 1), (25, 30, "jog-plus", 1)]
            + [(25, 30, "jog-minus", 1), (35, 40, "jog-plus", 1), (35, 50, "maxvel", -3.0)]
            + [(45, 50, "jog-minus", 1), (50, 55, "jog-plus", 1), (50, 55, "maxvel", 0.001)]
            + [(60, 70, "position-fb", 0.000005), (70, 80, "position-fb", 0.000014)]
            + [(80, 90, "position-fb", 0.000025), (90, 100, "position-fb", 0.0000149)]
            + [(100, 110, "position-fb", 0.0000249), (110, 120, "position-fb", 1e-5)]
            + [(120, 130, "position-fb", 0.0), (130, 140, "position-fb", NAN)]
            + [
                (140, 150, "position-fb", 0.5),
                (1200, n, "run", 1),
                (1200, 1205, "position-fb", NAN),
            ]
            + [(1205, n, "position-fb", 0.3), (1250, n, "run", 0)],
        ),
        # pause 1 s (and -1): the end is held 1000 periods, then left only
        # with position-fb still there; released during the pause, elapsed
        # keeps counting until the start is reached
        rows(
            n,
            [(5, 1200, "run", 1), (5, 1300, "pause", 1), (20, 1030, "position-fb", -1.0)]
            + [(1030, 1100, "position-fb", 0.0), (1100, 1250, "position-fb", 1.0)]
            + [(1250, n, "position-fb", 0.0)],
        ),
    ]
    write_test(
        "steptest-run",
        """steptest: position-fb streamed (not following position-cmd), so every
rule shows on its own: the ends of a run by dir (0, 1, 2 and 3 = both)
and amplitude (negative, 0, epsilon), arriving within epsilon, pause,
release and return to the start, jogs, the 1e-5 idle follow, NaN, a
larger epsilon on one channel.  test.hal from gen.py; expected recorded
from LinuxCNC 2.9 (README).""",
        chans,
        n,
        1000000,
        [0.001, 0.001, 0.1, 0.001],
    )


def loop_test() -> None:
    """steptest driving limit3 (standing in for a stepgen's motion) whose
    output is position-fb, as Stepconf's test runs it."""
    n = 1600
    ins = [p for p in INS if p != "position-fb"]
    ch = rows(
        n,
        [(5, 35, "jog-plus", 1), (45, 65, "jog-minus", 1), (45, 65, "maxvel", 5.0)]
        + [(75, 600, "run", 1), (950, 1250, "run", 1), (950, 1250, "dir", 1)]
        + [(950, 1250, "amplitude", 0.5), (1300, 1400, "run", 1), (1300, 1400, "dir", 2)]
        + [(1300, 1400, "amplitude", 0.3)],
    )
    d = HERE.parent / "steptest-loop"
    d.mkdir(exist_ok=True)
    comment = """steptest in a loop: position-cmd into limit3 (maxv 10, maxa 100, standing
in for stepgen's motion), limit3's output back to position-fb, as in
Stepconf's axis test: jogs, a run both ways, one positive only, one
negative only, each released and returned to its start.  Exact arrival
within epsilon depends on limit3's doubles (bit for bit 2.9's).  test.hal
from ../steptest-run/gen.py; expected recorded from LinuxCNC 2.9 (README)."""
    hal = [f"# {line}".rstrip() for line in comment.splitlines()]
    hal += ["loadrt threads name1=t period1=1000000", "loadrt steptest", "loadrt limit3"]
    cfg = "".join(IN_TYPE.get(p, "b") for p in ins)
    outs = OUTS + ["limit3-out"]
    ocfg = "".join("b" if p == "running" else "f" for p in outs)
    hal.append(f"loadrt streamer depth={n + 4} cfg={cfg}")
    hal.append(f"loadrt sampler depth={n + 4} cfg={ocfg}")
    hal += [f"net {p} streamer.0.pin.{j} => steptest.0.{p}" for j, p in enumerate(ins)]
    hal += [f"net {p} steptest.0.{p} => sampler.0.pin.{j}" for j, p in enumerate(OUTS)]
    hal.append("net position-cmd limit3.0.in")
    hal.append(f"net fb limit3.0.out => steptest.0.position-fb sampler.0.pin.{len(OUTS)}")
    hal += ["setp limit3.0.maxv 10", "setp limit3.0.maxa 100"]
    hal += ["addf streamer.0 t", "addf steptest.0 t", "addf limit3.0 t", "addf sampler.0 t"]
    text = "".join(
        " ".join(fmt(p, v) for p, v in zip(INS, r) if p != "position-fb") + "\n" for r in ch
    )
    (d / "in0.txt").write_text(text)
    hal += ["loadusr -w halstreamer in0.txt", "start", f"loadusr -w halsampler -n {n}", "stop"]
    hal.append("getp steptest.0.elapsed")
    (d / "test.hal").write_text("\n".join(hal) + "\n")


if __name__ == "__main__":
    run_test()
    loop_test()
