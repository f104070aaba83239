# SPDX-License-Identifier: GPL-2.0-or-later
"""The HAL examples of the seed documents, run with the result the seed states.

Each example is a file in examples/ written from the seed text (the header
names the seed file and lines, and every change from the seed with the
reason).  A test runs the example under ``halrun -S`` followed by the
measurements, and checks what the seed says happens.  README.md lists every
HAL example of the seeds and where it is tested, or why it cannot be.
Virtual parallel ports (vparport) stand in for real ones: ``@VPORT@`` (or
``@VPORT0@``...) in an example is the path of a port the test creates.
"""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "tests" / "e2e" / "parport"))
import pphelp as pp  # noqa: E402
from pphelp import bit, drive, probe, tag, values  # noqa: E402

EXAMPLES = HERE / "examples"


@pytest.fixture(autouse=True)
def _built() -> None:
    pp.require_built()


def example(name: str, tmp: Path, ports: int = 0) -> tuple[str, list[Path]]:
    """The example's text with its virtual ports created in tmp."""
    text = (EXAMPLES / f"{name}.hal").read_text()
    made = []
    for i in range(max(ports, 1 if "@VPORT@" in text else 0)):
        p = pp.create(tmp, f"vp{i}")
        made.append(p)
        text = text.replace(f"@VPORT{i}@", str(p))
        if i == 0:
            text = text.replace("@VPORT@", str(p))
    assert "@VPORT" not in text, f"{name}: a virtual port placeholder is left"
    return text, made


def run(tmp: Path, script: str) -> str:
    """Run under halrun -S; any failing line (the example's or ours) fails."""
    r = pp.halrun(tmp, script)
    assert r.returncode == 0, f"halrun failed ({r.returncode}):\n{r.stdout}\n{r.stderr}"
    return r.stdout


def getp(out: str, key: str) -> str:
    v = values(out)[key]
    assert len(v) == 1, v
    return v[0]


def pin_table(out: str) -> dict[str, tuple[str, str, str]]:
    """name -> (type, dir, value) from `show pin`/`show param` lines."""
    rows = {}
    for line in out.splitlines():
        w = line.split()
        if len(w) == 5 and w[0].isdigit():
            rows[w[4]] = (w[1], w[2], w[3])
    return rows


# ---- tutorial ----------------------------------------------------------------


def test_siggen_tutorial(tmp_path: Path) -> None:
    """siggen shows up as an RT component with the seed's nine pins (ours has
    2.9's reset pin too), an FP function, a thread that runs it, and `save`
    prints the commands that rebuild the configuration."""
    text, _ = example("siggen-tutorial", tmp_path)
    out = run(tmp_path, text)
    assert re.search(r"^ +\d+  RT    siggen +ready$", out, re.M)
    pins = pin_table(out)
    for name, typ, d in [
        ("amplitude", "float", "IN"),
        ("clock", "bit", "OUT"),
        ("cosine", "float", "OUT"),
        ("frequency", "float", "IN"),
        ("offset", "float", "IN"),
        ("sawtooth", "float", "OUT"),
        ("sine", "float", "OUT"),
        ("square", "float", "OUT"),
        ("triangle", "float", "OUT"),
    ]:
        assert pins[f"siggen.0.{name}"][:2] == (typ, d), name
    assert re.search(r"YES +0 +siggen\.0\.update$", out, re.M)
    assert re.search(r"test-thread .*\n +1 siggen\.0\.update", out)
    save = out[out.rindex("# components") :]
    for line in (
        "loadrt threads name1=test-thread period1=1000000",
        "loadrt siggen",
        "addf siggen.0.update test-thread",
    ):
        assert line in [ln.rstrip() for ln in save.splitlines()]


def test_halmeter_tutorial(tmp_path: Path) -> None:
    """With amplitude 5 the cosine swings between -5 and +5."""
    text, _ = example("halmeter-tutorial", tmp_path)
    script = text + "stop\nloadusr -w echo @@c\n" + "simrun 10ms\ngetp siggen.0.cosine\n" * 100
    c = [float(x) for x in values(run(tmp_path, script))["c"]]
    assert len(c) == 100
    assert max(c) == pytest.approx(5, abs=0.01) and min(c) == pytest.approx(-5, abs=0.01)
    assert all(-5.0000001 <= x <= 5.0000001 for x in c)


def _rising(log: list[tuple[int, dict[int, int]]], pin: int) -> list[int]:
    out, prev = [], 0
    for t, lv in log:
        if lv[pin] and not prev:
            out.append(t)
        prev = lv[pin]
    return out


def test_stepgen_tutorial_10khz(tmp_path: Path) -> None:
    """Velocity 1.000 x 10000 steps/inch = 10 kHz: step counts per 10 ms
    window follow 10000 |cos(2 pi t)| (stepgen 0) and 10000 |sin| (stepgen
    1), peaking at 100 steps per window; the direction flips at the zero
    crossings.  Steps are counted on a virtual parallel port."""
    text, _ = example("stepgen-tutorial", tmp_path)
    port = pp.create(tmp_path, "steps")
    script = (
        text
        + f'loadrt hal_parport cfg="sim:{port} out"\naddf parport.0.write fast\n'
        + "net xs stepgen.0.step => parport.0.pin-02-out\n"
        + "net xd stepgen.0.dir => parport.0.pin-03-out\n"
        + "net ys stepgen.1.step => parport.0.pin-04-out\n"
        + "simrun 1s\n"
    )
    run(tmp_path, script)
    log = pp.log(port, 2, 3, 4)
    for pin, fn in ((2, math.cos), (4, math.sin)):
        rises = _rising(log, pin)
        for w in range(1, 100):  # window 0 holds the start (first update at 1 ms)
            a, b = w * 0.01, (w + 1) * 0.01
            n = sum(1 for t in rises if a * 1e9 <= t < b * 1e9)
            # steps in [a, b) = 10000 * integral of |f(2 pi t)| dt (1 ms lag, +-2)
            want = 10000 * _abs_integral(fn, a - 0.001, b - 0.001)
            assert abs(n - want) <= 3, f"pin {pin} window {w}: {n} steps, want {want:.1f}"
        assert max(sum(1 for t in rises if w * 1e7 <= t < (w + 1) * 1e7) for w in range(100)) in (
            99,
            100,
        )
    dir_changes = [t for (t, lv), (_, pv) in zip(log[1:], log) if lv[3] != pv[3]]
    # the direction turns with the first step after each zero crossing
    assert len(dir_changes) == 2
    assert all(abs(t / 1e9 - z) < 0.01 for t, z in zip(dir_changes, (0.25, 0.75)))


def _abs_integral(fn: object, a: float, b: float, n: int = 200) -> float:
    f = fn  # type: ignore[assignment]
    h = (b - a) / n
    return sum(abs(f(2 * math.pi * (a + (i + 0.5) * h))) * h for i in range(n))  # type: ignore


# ---- logic and conversion ----------------------------------------------------


def test_and2_parport(tmp_path: Path) -> None:
    """Pin 14 is on exactly when pins 11 and 12 are on."""
    text, (port,) = example("and2-parport", tmp_path)
    script = text
    for k, (a, b) in enumerate([(0, 0), (0, 1), (1, 0), (1, 1)]):
        script += drive(port, {11: a, 12: b}) + "simrun 2ms\n" + probe(f"v{k}", port, 14)
    out = run(tmp_path, script)
    v = values(out)
    assert [pp.levels(v[f"v{k}"][0])[14] for k in range(4)] == [0, 0, 0, 1]


def test_weighted_sum(tmp_path: Path) -> None:
    """Bits 0 and 2 true, weights 1, 2, 4, 8, no offset: the sum is 5."""
    text, _ = example("weighted-sum", tmp_path)
    names = [f"wsum.0.bit.{m}.weight" for m in range(4)] + ["wsum.0.offset", "wsum.0.sum"]
    out = run(tmp_path, text + "simrun 1ms\n" + tag("v", *names))
    assert values(out)["v"] == ["1", "2", "4", "8", "0", "5"]


def test_lut5_0xa(tmp_path: Path) -> None:
    """function 0xa: TRUE for bit 0 alone and for bits 0 and 1, else FALSE."""
    text, _ = example("lut5-two-input", tmp_path)
    script = text
    for k in range(32):
        for b in range(5):
            script += f"setp lut5.0.in-{b} {(k >> b) & 1}\n"
        script += "simrun 1ms\n" + tag(f"v{k}", "lut5.0.out")
    out = run(tmp_path, script)
    assert [bit(getp(out, f"v{k}")) for k in range(32)] == [(0xA >> k) & 1 for k in range(32)]


def test_mux4_load(tmp_path: Path) -> None:
    text, _ = example("mux4-load", tmp_path)
    out = run(
        tmp_path,
        text + "setp mux4.0.in2 7\nsetp mux4.0.sel1 1\nsimrun 1ms\n" + tag("v", "mux4.0.out"),
    )
    assert float(getp(out, "v")) == 7


def test_logic_personality(tmp_path: Path) -> None:
    """The seed's pins, and each gate computing its function."""
    text, _ = example("logic-personality", tmp_path)
    out = run(tmp_path, text + "show pin logic\n")
    pins = {p for p in pin_table(out) if not p.endswith(".time")}  # the functions' timing pins
    want = {"logic.0.and", "logic.0.in-00", "logic.0.in-01"}
    want |= {"logic.1.and", "logic.1.or"} | {f"logic.1.in-0{i}" for i in range(5)}
    want |= {"logic.2.and", "logic.2.xor"} | {f"logic.2.in-0{i}" for i in range(3)}
    assert pins == want
    script = text
    for k in range(8):
        for i in range(3):
            script += f"setp logic.2.in-0{i} {(k >> i) & 1}\n"
        script += "simrun 1ms\n" + tag(f"v{k}", "logic.2.and", "logic.2.xor")
    out = run(tmp_path, script)
    for k in range(8):
        ones = bin(k).count("1")
        assert [bit(s) for s in values(out)[f"v{k}"]] == [int(k == 7), ones % 2]


# ---- load lines of the component chapters ----------------------------------


def test_stepgen_load(tmp_path: Path) -> None:
    """0 and 1: step type 0 in position mode; 2: quadrature in velocity mode."""
    text, _ = example("stepgen-load", tmp_path)
    pins = set(pin_table(run(tmp_path, text + "show pin stepgen\n")))
    for n in (0, 1):
        assert {f"stepgen.{n}.{p}" for p in ("position-cmd", "step", "dir")} <= pins
        assert f"stepgen.{n}.velocity-cmd" not in pins
    assert {"stepgen.2.velocity-cmd", "stepgen.2.phase-A", "stepgen.2.phase-B"} <= pins
    assert not {"stepgen.2.position-cmd", "stepgen.2.step", "stepgen.3.enable"} & pins


def test_pwmgen_load(tmp_path: Path) -> None:
    text, _ = example("pwmgen-load", tmp_path)
    pins = set(pin_table(run(tmp_path, text + "show pin pwmgen\n")))
    outs = {p.split(".", 2)[1] + "." + p.split(".", 2)[2] for p in pins}
    assert {"0.pwm"} <= outs and not {"0.dir", "0.up"} & outs
    assert {"1.pwm", "1.dir"} <= outs and "1.up" not in outs
    assert {"2.up", "2.down"} <= outs and "2.pwm" not in outs
    assert "pwmgen.3.enable" not in pins


def test_debounce_groups(tmp_path: Path) -> None:
    """cfg=1,4,2: groups of 1, 4 and 2 filters; with delay 4 a glitch of four
    periods is rejected and a level held five periods gets through."""
    text, _ = example("debounce-load", tmp_path)
    out = run(tmp_path, text + "show pin debounce\n")
    ins = {p for p in pin_table(out) if p.endswith(".in")}
    assert ins == {"debounce.0.0.in"} | {f"debounce.1.{f}.in" for f in range(4)} | {
        "debounce.2.0.in",
        "debounce.2.1.in",
    }
    script = text + "setp debounce.1.2.in 1\nsimrun 4ms\nsetp debounce.1.2.in 0\nsimrun 4ms\n"
    script += tag("glitch", "debounce.1.2.out")
    script += "setp debounce.1.2.in 1\nsimrun 5ms\n" + tag("held", "debounce.1.2.out")
    v = values(run(tmp_path, script))
    assert v["glitch"] == ["FALSE"] and v["held"] == ["TRUE"]


def _instances(tmp_path: Path) -> dict[str, set[str]]:
    """Instance numbers per component after the seed's load lines without
    counts (function timing pins such as encoder.update-counters.time left out)."""
    text, _ = example("default-counts", tmp_path)
    out: dict[str, set[str]] = {}
    for p in pin_table(run(tmp_path, text + "show pin\n")):
        comp, inst = p.split(".")[:2]
        if inst.isdigit():
            out.setdefault(comp, set()).add(inst)
    return out


def test_default_counts(tmp_path: Path) -> None:
    """Without counts: one debounce group (of one filter), three encoders,
    one siggen."""
    inst = _instances(tmp_path)
    assert inst["debounce"] == {"0"} and inst["encoder"] == {"0", "1", "2"}
    assert inst["siggen"] == {"0"}


def test_pid_default_count(tmp_path: Path) -> None:
    """The seed: "If numchan is not specified, one loop will be installed"."""
    assert _instances(tmp_path)["pid"] == {"0"}


# ---- parallel port ---------------------------------------------------------


def test_parport_cfg_types(tmp_path: Path) -> None:
    """Port 0 defaults to out, port 1 is in, port 2 out: pins 2-9 follow."""
    text, _ = example("parport-cfg", tmp_path, ports=3)
    pins = set(pin_table(run(tmp_path, text + "show pin\n")))
    for p, kind in ((0, "out"), (1, "in"), (2, "out")):
        for n in range(2, 10):
            assert f"parport.{p}.pin-{n:02d}-{kind}" in pins


def test_parport_second_port(tmp_path: Path) -> None:
    """The second (input) port reads its data pins in the base thread."""
    text, (a, b) = example("parport-two-ports", tmp_path, ports=2)
    script = text + drive(b, {4: 0}) + "simrun 100us\n"
    script += tag("v", "parport.1.pin-04-in", "parport.1.pin-05-in")
    assert values(run(tmp_path, script))["v"] == ["FALSE", "TRUE"]


def test_parport_doublestep(tmp_path: Path) -> None:
    """stepspace 0 + reset: one step every base period at full speed, each
    reset-time (5 us) long."""
    text, (port,) = example("parport-doublestep", tmp_path)
    script = text + "setp stepgen.0.maxvel 0\nsetp stepgen.0.position-cmd 100000\nsimrun 20ms\n"
    run(tmp_path, script)
    log = pp.log(port, 2)
    rises = _rising(log, 2)
    assert len(rises) > 100
    gaps = {b - a for a, b in zip(rises[len(rises) // 2 :], rises[len(rises) // 2 + 1 :])}
    assert gaps == {50_000}
    widths = {t2 - t1 for (t1, l1), (t2, _) in zip(log, log[1:]) if l1[2] == 1}
    assert widths == {5000}


def test_probe_parport(tmp_path: Path) -> None:
    text, _ = example("probe-parport", tmp_path)
    out = run(tmp_path, text + "show comp\n")
    assert "probe_parport" in out and "hal_parport" in out


def test_halcmd_parport_commands(tmp_path: Path) -> None:
    """setp drives pin 8; linksp/linkps attach pins 2 and 3 to signals; sets
    then moves pin 2; unlinkp detaches it (the pin keeps its last value)."""
    text, (port,) = example("halcmd-parport", tmp_path)
    script = text + "simrun 100us\n" + probe("a", port, 2, 3, 8)
    script += "unlinkp parport.0.pin-02-out\nsets X-step FALSE\nsimrun 100us\n"
    script += probe("b", port, 2) + "show sig X-step\n"
    out = run(tmp_path, script)
    v = values(out)
    assert pp.levels(v["a"][0]) == {2: 1, 3: 0, 8: 1}
    assert pp.levels(v["b"][0]) == {2: 1}
    assert "parport.0.pin-02-out" not in out.split("X-step")[-1]


def test_standard_pinout(tmp_path: Path) -> None:
    """The step/dir signals reach their pins (read first, write last)."""
    text, (port,) = example("standard-pinout", tmp_path)
    script = text + "sets Xstep 1\nsets Zdir 1\nsimrun 100us\n" + probe("v", port, 2, 3, 6, 7)
    script += "show thread\n"
    out = run(tmp_path, script)
    assert pp.levels(values(out)["v"][0]) == {2: 0, 3: 1, 6: 1, 7: 0}
    assert re.search(r"1 parport\.0\.read\n +2 parport\.0\.write", out)


def test_winder(tmp_path: Path) -> None:
    """The start signal enables the stepgen: steps on pin 2 only while run."""
    text, (port,) = example("winder", tmp_path)
    script = text + "setp stepgen.0.position-scale 200\nsetp stepgen.0.velocity-cmd 5\n"
    script += "simrun 100ms\nsets run-stepgen 1\nsimrun 1s\nsets run-stepgen 0\nsimrun 100ms\n"
    run(tmp_path, script)
    rises = _rising(pp.log(port, 2), 2)
    assert rises and 100e6 <= rises[0] and rises[-1] <= 1.1e9
    assert abs(len(rises) - 1000) <= 2  # 5 units/s x 200 steps/unit for 1 s


# ---- examples with motion pins replaced by test signals --------------------


def test_compute_velocity(tmp_path: Path) -> None:
    """X moving at 15 IPM in the minus direction: X-IPM reads 15 (and the
    per-second velocity -0.25)."""
    text, _ = example("compute-velocity", tmp_path)
    script = text
    for k in range(10):
        script += f"sets xpos-cmd {-0.25 * 0.001 * k:.6f}\nsimrun 1ms\n"
    script += tag("v", "X-IPM", "X-IPS").replace("getp", "gets")
    v = values(run(tmp_path, script))["v"]
    assert float(v[0]) == pytest.approx(15, rel=1e-9)
    assert float(v[1]) == pytest.approx(-0.25, rel=1e-9)


def test_softstart(tmp_path: Path) -> None:
    """limit2 keeps the slope within maxv, limit3 within maxv and maxa,
    lowpass approaches the square wave exponentially (gain .01 a period);
    7 s cover the square wave's flip at 5 s and limit3's 1.2 s way from -1
    to +1 (0.2 s accelerating, 0.8 s at maxv, 0.2 s braking).  Sampled every
    20 ms."""
    text, _ = example("softstart", tmp_path)
    script = text + "loadusr -w echo @@rows\n"
    n, step = 350, 0.02
    for _ in range(n):
        script += "simrun 20ms\ngets lowpass\ngets limit2\ngets limit3\ngets square\n"
    flat = [float(x) for x in values(run(tmp_path, script))["rows"]]
    lp, l2, l3, sq = (flat[i::4] for i in range(4))  # values as gets prints them
    assert len(sq) == n and sq[0] == -1 and sq[-1] == 1
    assert max(abs(b - a) for a, b in zip(l2, l2[1:])) <= 2 * step + 1e-9
    vel = [(b - a) / step for a, b in zip(l3, l3[1:])]
    assert max(abs(x) for x in vel) <= 2 + 1e-5
    # mean velocities of adjacent windows differ by at most maxa x window
    assert max(abs(b - a) for a, b in zip(vel, vel[1:])) <= 10 * step + 1e-5
    assert min(vel) < -1.9 and max(vel) > 1.9  # it does move at maxv
    model = 0.0
    for k in range(n):
        for _ in range(20):  # 20 periods of 1 ms; the square is sampled at the end
            model += 0.01 * (sq[k] - model)
        if k not in (249, 250):  # the flip happens inside sample 250's window
            assert lp[k] == pytest.approx(model, rel=1e-6, abs=1e-7), k  # gets: 7 digits
        else:
            model = lp[k]
    assert l2[-1] == pytest.approx(1) and l3[-1] == pytest.approx(1, abs=1e-6)
    # limit3 at 6.0 s: 1.0 s after the flip, 0.2 short of the way
    assert l3[299] == pytest.approx(0.8, abs=0.01)


def test_spindle_scale(tmp_path: Path) -> None:
    """5000 RPM commanded gives 10 V."""
    text, _ = example("spindle-scale", tmp_path)
    script = text + "sets spindle-speed-scale 5000\nsimrun 1ms\n"
    v = values(run(tmp_path, script + tag("v", "spindle-dac").replace("getp", "gets")))
    assert float(v["v"][0]) == pytest.approx(10)


def test_spindle_at_speed(tmp_path: Path) -> None:
    """At speed when the measured speed is within a factor 1.01 of the command."""
    text, _ = example("spindle-at-speed", tmp_path)
    script = text
    for k, meas in enumerate([1000, 1009, 1011, 991, 989]):
        script += f"sets spindle-cmd 1000\nsets spindle-velocity {meas}\nsimrun 1ms\n"
        script += tag(f"v{k}", "spindle-at-speed").replace("getp", "gets")
    v = values(run(tmp_path, script))
    # in1/scale <= in2 <= in1*scale: 990.099 .. 1010
    assert [v[f"v{k}"][0] for k in range(5)] == ["TRUE", "TRUE", "FALSE", "TRUE", "FALSE"]
