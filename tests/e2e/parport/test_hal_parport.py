# SPDX-License-Identifier: GPL-2.0-or-later
"""hal_parport on virtual parallel ports (bin/vparport) under halrun -S.

The driver's register code runs unchanged against the virtual port's
register model (inverted status bit 7 and control bits 0, 1, 3, data
direction, ECR modes, open-collector control pins); the expected pin
levels come from the seed's tables in pphelp.py.
"""

from __future__ import annotations

import random
import subprocess
import sys
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import pphelp as pp  # noqa: E402
from pphelp import bit, create, drive, halrun, probe, tag, values  # noqa: E402

sys.path.insert(0, str(pp.ROOT / "tests" / "hal"))
import halnorm  # noqa: E402

PERIOD = 50_000


@pytest.fixture(autouse=True)
def _built() -> None:
    pp.require_built()


def setup(cfg: str, funcs: str = "read write") -> str:
    lines = f'loadrt hal_parport cfg="{cfg}"\nloadrt threads name1=t period1={PERIOD}\n'
    for f in funcs.split():
        lines += f"addf parport.0.{f} t\n" if "all" not in f else f"addf parport.{f} t\n"
    return lines


# ---- names ------------------------------------------------------------------


def test_listing_matches_linuxcnc(tmp_path: Path) -> None:
    """Pins, params and functions of an out and an x port, byte for byte as
    LinuxCNC 2.9 lists them (recorded, data/README.md)."""
    a, b = create(tmp_path, "A"), create(tmp_path, "B")
    r = halrun(
        tmp_path,
        f'loadrt hal_parport cfg="sim:{a} out sim:{b} x"\nshow comp\nshow pin\nshow param\n'
        "show funct\n",
        args=(),
    )
    assert r.returncode == 0, r.stderr
    ours = halnorm.normalize(r.stdout)
    ours = ours[ours.index("Loaded HAL Components:") :]
    want = (pp.HERE / "data" / "listing-out-x.txt").read_text()
    assert ours.rstrip("\n") == want.rstrip("\n")


@pytest.mark.parametrize("mode", ["out", "in", "epp", "x"])
def test_pin_sets(tmp_path: Path, mode: str) -> None:
    """Each type creates -out pins (with -invert/-reset params) for its output
    pins and -in/-in-not pins for its inputs, numbered as on the DB-25."""
    port = create(tmp_path, "p", "--ecr")
    r = halrun(tmp_path, f'loadrt hal_parport cfg="sim:{port} {mode}"\nshow pin\nshow param\n')
    assert r.returncode == 0, r.stderr
    pins = {ln.split()[-1] for ln in r.stdout.splitlines() if "parport.0.pin-" in ln}
    want = set()
    for n in pp.OUT_PINS[mode]:
        want |= {f"parport.0.pin-{n:02d}-out", f"parport.0.pin-{n:02d}-out-invert"}
        want.add(f"parport.0.pin-{n:02d}-out-reset")
    for n in pp.IN_PINS[mode]:
        want |= {f"parport.0.pin-{n:02d}-in", f"parport.0.pin-{n:02d}-in-not"}
    assert pins == want


# ---- outputs ----------------------------------------------------------------


@pytest.mark.parametrize("mode", ["out", "in", "epp", "x"])
def test_outputs_follow_pins_and_invert(tmp_path: Path, mode: str) -> None:
    """A TRUE -out pin is a high pin, -out-invert flips it; random vectors."""
    port = create(tmp_path, "p", "--ecr")
    rng = random.Random(f"outputs-{mode}")
    outs = pp.OUT_PINS[mode]
    script = setup(f"sim:{port} {mode}")
    expect = []
    for k in range(12):
        val = {n: rng.randint(0, 1) for n in outs}
        inv = {n: rng.randint(0, 1) for n in outs}
        for n in outs:
            script += f"setp parport.0.pin-{n:02d}-out {val[n]}\n"
            script += f"setp parport.0.pin-{n:02d}-out-invert {inv[n]}\n"
        script += f"simrun {PERIOD}\n" + probe(f"v{k}", port, *outs)
        expect.append({n: val[n] ^ inv[n] for n in outs})
    r = halrun(tmp_path, script)
    assert r.returncode == 0, r.stderr
    v = values(r.stdout)
    for k, want in enumerate(expect):
        assert pp.levels(v[f"v{k}"][0]) == want, f"vector {k}"


def test_outputs_only_change_at_write(tmp_path: Path) -> None:
    """Setting a pin does nothing to the port until write runs."""
    port = create(tmp_path)
    r = halrun(
        tmp_path,
        setup(f"sim:{port}", "read")
        + "setp parport.0.pin-02-out 1\n"
        + f"simrun {PERIOD}\n"
        + probe("before", port, 2)
        + f"addf parport.0.write t\nsimrun {PERIOD}\n"
        + probe("after", port, 2),
    )
    v = values(r.stdout)
    assert pp.levels(v["before"][0]) == {2: 0}
    assert pp.levels(v["after"][0]) == {2: 1}


# ---- inputs -----------------------------------------------------------------


@pytest.mark.parametrize("mode", ["out", "in", "epp", "x"])
def test_inputs_follow_the_pins(tmp_path: Path, mode: str) -> None:
    """-in is TRUE for a high pin, -in-not its complement (status bit 7 and
    control bits 0, 1, 3 are inverted by the port, not seen by the user)."""
    port = create(tmp_path, "p", "--ecr")
    rng = random.Random(f"inputs-{mode}")
    ins = pp.IN_PINS[mode]
    script = setup(f"sim:{port} {mode}")
    expect = []
    for k in range(12):
        lv = {n: rng.randint(0, 1) for n in ins}
        script += drive(port, lv) + f"simrun {PERIOD}\n"
        names = []
        for n in ins:
            names += [f"parport.0.pin-{n:02d}-in", f"parport.0.pin-{n:02d}-in-not"]
        script += tag(f"v{k}", *names)
        expect.append(lv)
    r = halrun(tmp_path, script)
    assert r.returncode == 0, r.stderr
    v = values(r.stdout)
    for k, lv in enumerate(expect):
        got = [bit(s) for s in v[f"v{k}"]]
        want = []
        for n in ins:
            want += [lv[n], 1 - lv[n]]
        assert got == want, f"vector {k}"


def test_undriven_inputs_read_high(tmp_path: Path) -> None:
    """Nothing attached: inputs float high (TRUE), as the seed's x-mode note says."""
    port = create(tmp_path)
    names = [f"parport.0.pin-{n:02d}-in" for n in pp.IN_PINS["x"]]
    r = halrun(tmp_path, setup(f"sim:{port} x") + f"simrun {PERIOD}\n" + tag("v", *names))
    assert values(r.stdout)["v"] == ["TRUE"] * len(names)


def test_x_mode_open_collector_test_of_the_seed(tmp_path: Path) -> None:
    """The seed's test for open-collector control pins: in x mode, a pin
    pulled to ground reads FALSE on an OC port; on a push-pull port it
    stays TRUE (and the port fights the load)."""
    oc, pp_port = create(tmp_path, "oc"), create(tmp_path, "pp", "--control-pp")
    for port, want in ((oc, "FALSE"), (pp_port, "TRUE")):
        r = halrun(
            tmp_path,
            setup(f"sim:{port} x")
            + f"simrun {PERIOD}\n"
            + tag("free", "parport.0.pin-14-in")
            + drive(port, {14: 0})
            + f"simrun {PERIOD}\n"
            + tag("grounded", "parport.0.pin-14-in"),
        )
        v = values(r.stdout)
        assert v["free"] == ["TRUE"] and v["grounded"] == [want], port
    assert pp.counters(oc)["contention"][0] == 0
    assert pp.counters(pp_port)["contention"][0] > 0


def test_in_mode_releases_data_lines(tmp_path: Path) -> None:
    """In mode turns the data drivers off: the outside drives pins 2-9 and
    nothing the driver does fights it."""
    port = create(tmp_path)
    r = halrun(
        tmp_path,
        setup(f"sim:{port} in")
        + drive(port, {n: n % 2 for n in pp.DATA})
        + f"simrun {PERIOD}\n"
        + tag("v", *[f"parport.0.pin-{n:02d}-in" for n in pp.DATA]),
    )
    assert r.returncode == 0, r.stderr
    assert [bit(s) for s in values(r.stdout)["v"]] == [n % 2 for n in pp.DATA]
    assert pp.counters(port)["contention"][0] == 0


# ---- ECR and bidirectional ports -------------------------------------------


@pytest.mark.parametrize("mode,ecr", [("out", 0x15), ("x", 0x15), ("in", 0x35), ("epp", 0x95)])
def test_ecr_mode(tmp_path: Path, mode: str, ecr: int) -> None:
    """On an ECP port (ECR at base+0x402, power-on SPP mode) in selects PS/2
    byte mode so the direction bit works, epp selects EPP mode; out and x
    leave the ECR alone."""
    port = create(tmp_path, "p", "--ecr")
    r = halrun(tmp_path, setup(f"sim:{port} {mode}") + "loadusr -w echo @@loaded\n", args=())
    assert r.returncode == 0, r.stderr
    # the session has ended; the registers keep what the driver wrote
    assert pp.register(port, "ecr") == ecr


def test_in_mode_on_spp_only_port_is_refused(tmp_path: Path) -> None:
    """An SPP-only port cannot read its data lines: a clear error, nothing
    loaded, the port released."""
    port = create(tmp_path, "p", "--spp")
    r = halrun(
        tmp_path, f'loadrt hal_parport cfg="sim:{port} in"\nshow comp\nshow pin\n', args=("-k",)
    )
    out = r.stdout + r.stderr
    assert f"port sim:{port} cannot be an input port" in out
    assert "hal_parport" not in pp.section(r.stdout, "Loaded HAL Components:")
    assert "parport." not in r.stdout
    assert pp.owner(port) == 0


# ---- register traffic -------------------------------------------------------


@pytest.mark.parametrize(
    "mode,reads",
    [("out", {"status": 1}), ("in", {"status": 1, "data": 1}), ("x", {"status": 1, "control": 1})],
)
def test_register_accesses_per_period(tmp_path: Path, mode: str, reads: dict[str, int]) -> None:
    """read reads the status register (+ data in in mode, + control in x mode)
    once; write writes data (not in in mode) and control once."""
    port = create(tmp_path)
    r = halrun(
        tmp_path,
        setup(f"sim:{port} {mode}")
        + f"loadusr -w {pp.VPARPORT} counters {port} --reset\n"
        + f"simrun {10 * PERIOD}\n",
    )
    assert r.returncode == 0, r.stderr
    c = pp.counters(port)
    for reg in ("data", "status", "control", "ecr", "other"):
        assert c[reg][0] == 10 * reads.get(reg, 0), reg
    assert c["data"][1] == (0 if mode == "in" else 10)
    assert c["control"][1] == 10
    assert c["status"][1] == c["ecr"][1] == c["other"][1] == 0


# ---- reset (DoubleStep) -----------------------------------------------------


def test_reset_ends_the_pulse_reset_time_after_write(tmp_path: Path) -> None:
    """The seed's DoubleStep: write sets the pin, reset (later in the same
    thread) puts it back reset-time later; pins without -out-reset keep
    their level; an inverted pin resets to its -out-invert level."""
    port = create(tmp_path)
    r = halrun(
        tmp_path,
        setup(f"sim:{port}", "write reset")
        + "setp parport.0.reset-time 5000\n"
        + "setp parport.0.pin-02-out-reset 1\nsetp parport.0.pin-02-out 1\n"
        + "setp parport.0.pin-03-out-reset 1\nsetp parport.0.pin-03-out-invert 1\n"
        + "setp parport.0.pin-03-out 1\n"
        + "setp parport.0.pin-04-out 1\n"
        + "setp parport.0.pin-01-out-reset 1\nsetp parport.0.pin-01-out 1\n"
        + f"simrun {PERIOD}\n",
    )
    assert r.returncode == 0, r.stderr
    edges = pp.log(port, 1, 2, 3, 4)
    t0 = PERIOD
    assert edges[-2:] == [
        (t0, {1: 1, 2: 1, 3: 0, 4: 1}),
        (t0 + 5000, {1: 0, 2: 0, 3: 1, 4: 1}),
    ]


def test_reset_time_limited_to_a_quarter_period(tmp_path: Path) -> None:
    """As LinuxCNC 2.9 (data/README.md): reset-time above period/4 is lowered."""
    port = create(tmp_path)
    r = halrun(
        tmp_path,
        setup(f"sim:{port}", "write reset")
        + "setp parport.0.reset-time 40000\nsetp parport.0.pin-05-out-reset 1\n"
        + f"setp parport.0.pin-05-out 1\nsimrun {PERIOD}\n"
        + tag("rt", "parport.0.reset-time"),
    )
    assert values(r.stdout)["rt"] == [str(PERIOD // 4)]
    assert [t for t, _ in pp.log(port, 5)][-2:] == [PERIOD, PERIOD + PERIOD // 4]


def test_reset_one_step_per_period(tmp_path: Path) -> None:
    """With reset the pin pulses every period (what stepgen's doublefreq
    relies on): one rising edge per period, reset-time wide."""
    port = create(tmp_path)
    r = halrun(
        tmp_path,
        setup(f"sim:{port}", "write reset")
        + "setp parport.0.reset-time 8000\nsetp parport.0.pin-02-out-reset 1\n"
        + f"setp parport.0.pin-02-out 1\nsimrun {20 * PERIOD}\n",
    )
    assert r.returncode == 0, r.stderr
    log = pp.log(port, 2)
    rises = [t for t, lv in log if lv[2] == 1]
    falls = [t for t, lv in log if lv[2] == 0]
    assert rises == [PERIOD * k for k in range(1, 21)]
    assert falls == [PERIOD * k + 8000 for k in range(1, 21)]


# ---- several ports ----------------------------------------------------------


def test_read_all_write_all_two_ports(tmp_path: Path) -> None:
    a, b = create(tmp_path, "A"), create(tmp_path, "B")
    r = halrun(
        tmp_path,
        f'loadrt hal_parport cfg="sim:{a} out sim:{b} in"\n'
        f"loadrt threads name1=t period1={PERIOD}\n"
        "addf parport.read-all t\naddf parport.write-all t\n"
        "setp parport.0.pin-09-out 1\nsetp parport.1.pin-17-out 1\n"
        + drive(a, {12: 0})
        + drive(b, {5: 0, 12: 0})
        + f"simrun {PERIOD}\n"
        + probe("a", a, 9)
        + probe("b", b, 17)
        + tag("in", "parport.0.pin-12-in", "parport.1.pin-05-in", "parport.1.pin-12-in"),
    )
    v = values(r.stdout)
    assert pp.levels(v["a"][0]) == {9: 1} and pp.levels(v["b"][0]) == {17: 1}
    assert v["in"] == ["FALSE", "FALSE", "FALSE"]


# ---- loading, unloading, errors ---------------------------------------------


def test_unload_releases_the_port(tmp_path: Path) -> None:
    port = create(tmp_path)
    r = halrun(
        tmp_path,
        f'loadrt hal_parport cfg="sim:{port}"\nunloadrt hal_parport\n'
        f'loadrt hal_parport cfg="sim:{port} x"\nshow pin parport.0.pin-01\n',
        args=("-k",),
    )
    assert r.returncode == 0, r.stderr
    assert "parport.0.pin-01-in" in r.stdout
    assert pp.owner(port) == 0


def test_busy_port(tmp_path: Path) -> None:
    """A port held by another HAL session is refused with who holds it."""
    port = create(tmp_path)
    first = subprocess.Popen(
        [str(pp.HALRUN), "-S"],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env={**__import__("os").environ, "HAL_INSTANCE": "pp-busy-" + tmp_path.name[-8:]},
    )
    try:
        assert first.stdin is not None
        first.stdin.write(f'loadrt hal_parport cfg="sim:{port}"\n')
        first.stdin.flush()
        for _ in range(200):
            if pp.owner(port):
                break
            time.sleep(0.05)
        holder = pp.owner(port)
        assert holder
        r = halrun(tmp_path, f'loadrt hal_parport cfg="sim:{port}"\nshow comp\n', args=("-k",))
        out = r.stdout + r.stderr
        assert f"virtual port {port} is busy (claimed by process {holder})" in out
        assert "hal_parport" not in pp.section(r.stdout, "Loaded HAL Components:")
    finally:
        first.communicate("quit\n", timeout=60)
    assert pp.owner(port) == 0


BAD_CFG = [
    ("", "cfg: no ports configured"),
    ("in", "cfg: type 'in' must follow a port address"),
    ("{A} in out", "cfg: type 'out' must follow a port address (one type per port)"),
    ("{A} foo", "cfg: bad port address 'foo'"),
    ("{A} IN", "cfg: bad port address 'IN'"),
    ("0x378_in", "cfg: bad port address '0x378_in'"),
    ("{A} {A}", "is given twice (ports 0 and 1)"),
    ("0x378 raw:0x378", "cfg: port 'raw:0x378' is given twice"),
    ("1 2 3 4 5 6 7 8 9", "cfg: more than 8 ports ('9')"),
    ("raw:0x3", "cfg: bad raw port 'raw:0x3'"),
    ("raw:0x378,junk", "cfg: bad raw port 'raw:0x378,junk'"),
    ("0x10000", "cfg: bad port address '0x10000'"),
    ("bogus:1", "cfg: unknown port kind in 'bogus:1'"),
    ("sim:", "cfg: port 'sim:' names nothing after the ':'"),
    ("sim:{missing}", "No such file or directory (create it with: vparport create NAME)"),
    ("15", "Linux parallel port 15 not found (no /dev/parport15"),
    ("ppdev:/nonexistent/parport0", "ppdev /nonexistent/parport0: open failed: No such file"),
    ("ppdev:/nonexistent/parport0 x", "x mode needs the control pins' levels"),
    ("gpiod:gpiochip0:1/2", "need 17 line offsets, one per pin 1..17"),
    ("gpiod:gpiochip0:1/2/3/4/5/6/7/8/9/10/11/12/13/14/15/16/16", "line 16 used twice"),
    ("gpiod:nosuchchip:1/2/3/4/5/6/7/8/9/10/11/12/13/14/15/16/-", "cannot open GPIO chip"),
    ("{A} sim:{missing}", "No such file or directory"),
]


@pytest.mark.parametrize("cfg,msg", BAD_CFG, ids=[c for c, _ in BAD_CFG])
def test_bad_cfg_loads_nothing(tmp_path: Path, cfg: str, msg: str) -> None:
    """A clear error naming the word or port, no component, no pins, and
    ports opened before the failure are released."""
    a = create(tmp_path, "A")
    cfg = cfg.format(A=f"sim:{a}", missing=tmp_path / "missing")
    r = halrun(
        tmp_path, f'loadrt hal_parport cfg="{cfg}"\nshow comp\nshow pin\nshow funct\n', args=("-k",)
    )
    out = r.stdout + r.stderr
    assert msg in out
    assert "hal_parport: " in out
    assert "insmod for hal_parport failed" in out
    assert "hal_parport" not in pp.section(r.stdout, "Loaded HAL Components:")
    assert "parport." not in r.stdout
    assert pp.owner(a) == 0


def test_probe_parport(tmp_path: Path) -> None:
    """probe_parport loads before hal_parport, creates nothing, unloads."""
    port = create(tmp_path)
    r = halrun(
        tmp_path,
        f'loadrt probe_parport\nloadrt hal_parport cfg="sim:{port}"\nshow comp\n'
        "show pin probe\nunloadrt probe_parport\nshow comp\n",
    )
    assert r.returncode == 0, r.stderr
    comps = r.stdout.split("Loaded HAL Components:")
    assert "probe_parport" in comps[1] and "hal_parport" in comps[1]
    assert "probe_parport" not in comps[2] and "hal_parport" in comps[2]
