# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2_sim inproc=1: the virtual 5i20 running inside rtapi_app
(lib/libvboard_inproc.so) against the same board behind a bin/vboard
socket.  One HAL sequence (stepgen moving with its Step/Dir looped into
encoder 0, a GPIO looped into another, a watchdog bite) runs against
both; every hm2 pin and parameter value (all but the timing ones) must be
identical at each checkpoint, and the values must also be what the
sequence implies (the encoder counts what the stepgen stepped, the
stepgen reaches its command, the watchdog bites).  Bad input: unknown
board or firmware, the board library missing, a bad loop, socket= with
inproc=1, lockstep on the wall clock: a clear error and nothing of
hm2_sim left in HAL."""

from __future__ import annotations

import os
import re
import subprocess
import uuid
from pathlib import Path

import pytest

from hm2e2e import BUILD, HALRUN, PFX, SEED_CONFIG, needs_vboard, vboard

pytestmark = needs_vboard

LIB = BUILD / "lib" / "libvboard_inproc.so"
# Step/Dir of stepgen 0 into encoder 0 A/B (as docs/hm2_sim.md), IOPort pin
# 0 into IOPort pin 71.
LOOPS = [(48, 3, False), (49, 2, True), (0, 71, False)]


def run_hal(
    tmp: Path, script: str, simclock: bool = True, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    f = tmp / f"t{uuid.uuid4().hex[:6]}.hal"
    f.write_text(script)
    e = dict(os.environ)
    e["HAL_INSTANCE"] = "hm2-inproc-" + uuid.uuid4().hex[:10]
    e["HM_BUILD"] = str(BUILD)
    e.pop("HM2_FIRMWARE_PATH", None)
    e.update(env or {})
    opts = ["-k"] + (["-S"] if simclock else [])
    r = subprocess.run(
        [str(HALRUN), *opts, "-f", str(f)],
        capture_output=True,
        text=True,
        timeout=300,
        env=e,
        cwd=tmp,
    )
    out = r.stdout + r.stderr
    for bad in ("AddressSanitizer", "LeakSanitizer", "runtime error:"):
        assert bad not in out, out
    return r


def sequence(loadline: str) -> str:
    """The HAL sequence, with '@@name' markers before each snapshot."""
    snap = "loadusr -w echo @@{0}\nshow pin {1}.\nshow param {1}.\n"
    return (
        "loadrt hostmot2\n" + loadline + "\nloadrt threads name1=servo period1=1000000\n"
        f"addf {PFX}.read servo\naddf {PFX}.write servo\n"
        f"setp {PFX}.stepgen.00.position-scale 1000\n"
        f"setp {PFX}.stepgen.00.steplen 5000\n"
        f"setp {PFX}.stepgen.00.stepspace 5000\n"
        f"setp {PFX}.stepgen.00.maxvel 25\n"
        f"setp {PFX}.stepgen.00.maxaccel 1000\n"
        f"setp {PFX}.stepgen.00.enable 1\n"
        f"setp {PFX}.encoder.00.counter-mode 1\n"
        f"setp {PFX}.watchdog.timeout_ns 5000000\n"
        f"setp {PFX}.gpio.000.is_output 1\n"
        f"setp {PFX}.gpio.000.out 1\n"
        f"setp {PFX}.pwmgen.00.enable 1\n"
        f"setp {PFX}.pwmgen.00.value 0.3\n"
        f"setp {PFX}.stepgen.00.position-cmd 0.25\n"
        "simrun 40ms\n" + snap.format("moving", PFX) + "simrun 80ms\n"
        f"setp {PFX}.gpio.000.out 0\n"
        f"setp {PFX}.stepgen.00.position-cmd -0.1\n"
        "simrun 60ms\n" + snap.format("back", PFX) + f"delf {PFX}.write servo\n"
        "simrun 30ms\n" + snap.format("bitten", PFX)
    )


TIMING = (".time", ".tmax", ".tmax-increased")


def snapshots(out: str) -> dict[str, dict[str, str]]:
    """Per marker: every pin/param name -> value, timing objects left out."""
    res: dict[str, dict[str, str]] = {}
    cur: dict[str, str] | None = None
    for line in out.splitlines():
        if line.startswith("@@"):
            cur = res.setdefault(line[2:].strip(), {})
            continue
        f = line.split()
        if cur is None or len(f) < 5 or not any(w.startswith(PFX + ".") for w in f):
            continue
        name = next(w for w in f if w.startswith(PFX + "."))
        if name.endswith(TIMING):
            continue
        # "owner type dir value name [==> sig]" (pins), "owner type dir value name" (params)
        cur[name] = f[3]
    return res


def socket_loadline(sock: Path) -> str:
    return f'loadrt hm2_sim socket={sock} board=5i20 config="{SEED_CONFIG}"'


def inproc_loadline(extra: str = "") -> str:
    loops = " ".join(f"{a}:{b}{':inv' if inv else ''}" for a, b, inv in LOOPS)
    return f'loadrt hm2_sim inproc=1 board=5i20 loops="{loops}" config="{SEED_CONFIG}" {extra}'


def test_same_pins_as_the_socket_board(tmp_path: Path) -> None:
    args = []
    for a, b, inv in LOOPS:
        args += ["--loop", f"{a}:{b}{':inv' if inv else ''}"]
    with vboard.VBoardProcess(tmp_path / "b.sock", "5i20", args=args) as vb:
        rs = run_hal(tmp_path, sequence(socket_loadline(Path(vb.socket_path))))
    ri = run_hal(tmp_path, sequence(inproc_loadline()))
    assert rs.returncode == 0, rs.stdout + rs.stderr
    assert ri.returncode == 0, ri.stdout + ri.stderr
    assert (
        f"{PFX}: initialized virtual AnyIO board in this process (SVST8_4)" in ri.stdout + ri.stderr
    )
    s, i = snapshots(rs.stdout), snapshots(ri.stdout)
    assert list(s) == ["moving", "back", "bitten"], rs.stdout
    for mark in s:
        assert len(s[mark]) > 300, s[mark]  # every pin and parameter of the board
        diff = {
            k: (s[mark].get(k), i[mark].get(k))
            for k in s[mark].keys() | i[mark].keys()
            if s[mark].get(k) != i[mark].get(k)
        }
        assert not diff, f"{mark}: socket vs in-process differ: {diff}"
    # ... and the values are the ones the sequence implies.
    v = i["moving"]
    counts = int(v[f"{PFX}.stepgen.00.counts"])
    assert 0 < counts <= 250  # 40 ms at <= 25 units/s of 1000 counts/unit, moving up
    assert int(v[f"{PFX}.encoder.00.count"]) == counts  # Step/Dir looped into A/B
    assert v[f"{PFX}.gpio.071.in"] == "TRUE" and v[f"{PFX}.watchdog.has_bit"] == "FALSE"
    v = i["back"]
    assert int(v[f"{PFX}.stepgen.00.counts"]) == -100
    assert int(v[f"{PFX}.encoder.00.count"]) == -100
    assert v[f"{PFX}.gpio.071.in"] == "FALSE"
    assert i["bitten"][f"{PFX}.watchdog.has_bit"] == "TRUE"


def nothing_left(out: str) -> None:
    """After a failed load: no hm2_sim component and no hm2 pin in HAL."""
    marker = out.split("@@after", 1)  # stdout only: the errors are on stderr
    assert len(marker) == 2, out
    assert "hm2_sim" not in marker[1] and PFX not in marker[1], out


AFTER = "loadusr -w echo @@after\nshow comp\nshow pin\n"


@pytest.mark.parametrize(
    "loadline,message",
    [
        (
            'loadrt hm2_sim inproc=1 board=5i20 firmware=NOPE config="num_encoders=1"',
            "firmware NOPE is not built into this vboard for board 5i20 (built: ",
        ),
        (
            "loadrt hm2_sim inproc=1 board=9z99 firmware=SVST8_4",
            "no in-process local-bus board '9z99' (built: ",
        ),
        (
            f'loadrt hm2_sim inproc=1 board=5i20 loops="48:3 49-2" config="{SEED_CONFIG}"',
            "hm2_sim: bad loop '49-2': want FROM:TO or FROM:TO:inv",
        ),
        (
            f'loadrt hm2_sim inproc=1 board=5i20 loops="48:999" config="{SEED_CONFIG}"',
            "hm2_sim: loop 48:999: ",
        ),
        (
            "loadrt hm2_sim inproc=1 socket=/tmp/x.sock board=5i20",
            "socket=/tmp/x.sock makes no sense with it",
        ),
        ("loadrt hm2_sim inproc=2 board=5i20", "hm2_sim: inproc=2 freerun=0: want 0 or 1"),
        (
            "loadrt hm2_sim socket=/tmp/x.sock freerun=1",
            "firmware=, loops= and freerun= are for in-process boards (inproc=1)",
        ),
        ("loadrt hm2_sim inproc=1", "no board given"),
        (
            'loadrt hm2_sim inproc=1 board=5i20 config="firmware=hm2/5i20/missing.BIT"',
            "missing.BIT",
        ),
    ],
)
def test_bad_input_leaves_nothing(tmp_path: Path, loadline: str, message: str) -> None:
    r = run_hal(tmp_path, "loadrt hostmot2\n" + loadline + "\n" + AFTER)
    out = r.stdout + r.stderr
    assert r.returncode != 0, out
    assert message in out, out
    nothing_left(r.stdout)


def test_board_library_missing(tmp_path: Path) -> None:
    missing = tmp_path / "nowhere" / "libvboard_inproc.so"
    r = run_hal(
        tmp_path,
        "loadrt hostmot2\n" + inproc_loadline() + "\n" + AFTER,
        env={"HM2_SIM_INPROC_LIB": str(missing)},
    )
    out = r.stdout + r.stderr
    assert r.returncode != 0, out
    assert f"hm2_sim: inproc=1: cannot load the in-process board library {missing}" in out
    nothing_left(r.stdout)
    # A file that is not the board library: refused by its entry point.
    r = run_hal(
        tmp_path,
        "loadrt hostmot2\n" + inproc_loadline() + "\n" + AFTER,
        env={"HM2_SIM_INPROC_LIB": str(BUILD / "lib" / "libhal.so")},
    )
    out = r.stdout + r.stderr
    assert r.returncode != 0 and "is not an in-process board library of this build" in out, out
    nothing_left(r.stdout)


def test_lockstep_refused_on_the_wall_clock(tmp_path: Path) -> None:
    r = run_hal(tmp_path, "loadrt hostmot2\n" + inproc_loadline() + "\n" + AFTER, simclock=False)
    out = r.stdout + r.stderr
    assert r.returncode != 0, out
    assert "runs in lockstep with HAL's clock but this HAL session runs on the wall clock" in out
    nothing_left(r.stdout)
    # host_time=0: the board's clocks stand still, registers still answer.
    r = run_hal(
        tmp_path,
        "loadrt hostmot2\n" + inproc_loadline("host_time=0") + f"\ngetp {PFX}.watchdog.has_bit\n",
        simclock=False,
    )
    assert r.returncode == 0, r.stdout + r.stderr
    assert r.stdout.split()[-1] == "FALSE" or "FALSE" in r.stdout, r.stdout


def test_library_exports_one_entry_point() -> None:
    assert LIB.exists(), f"{LIB} not built"
    nm = subprocess.run(
        ["nm", "-D", "--defined-only", str(LIB)], capture_output=True, text=True, check=True
    )
    names = [line.split()[-1] for line in nm.stdout.splitlines() if line.strip()]
    assert names == ["vbi_get_api"], names


def test_stats_line(tmp_path: Path) -> None:
    """stats=1: one line per board at unload."""
    r = run_hal(
        tmp_path,
        "loadrt hostmot2\n"
        + inproc_loadline("stats=1")
        + f"\nloadrt threads name1=servo period1=1000000\naddf {PFX}.read servo\n"
        f"addf {PFX}.write servo\nsimrun 7ms\n",
    )
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    m = re.search(
        rf"{PFX}: in-process board: (\d+) cycles \(queued reads \+ writes\); per cycle "
        r"(\d+) ns in the board calls, "
        r"(\d+) ns in the model, (-?\d+) ns transport; ([\d.]+) words read, ([\d.]+) written",
        out,
    )
    assert m, out
    calls, model, transport = int(m.group(2)), int(m.group(3)), int(m.group(4))
    assert int(m.group(1)) == 8  # 7 servo periods and hostmot2's transfer at load
    assert abs(calls - model - transport) <= 1 and 0 < model and 0 <= transport < calls
    assert float(m.group(5)) > 0 and float(m.group(6)) > 0


def test_freerun_on_the_wall_clock(tmp_path: Path) -> None:
    """freerun=1: the board runs on its own thread with the wall clock (as
    vboard --freerun), so a wall-clock session works and the stepgen steps
    while HAL only sleeps."""
    sg = f"{PFX}.stepgen.00"
    script = (
        "loadrt hostmot2\n"
        + inproc_loadline("freerun=1")
        + f"\nloadrt threads name1=servo period1=1000000\naddf {PFX}.read servo\n"
        f"addf {PFX}.write servo\nsetp {sg}.enable 1\nsetp {sg}.control-type 1\n"
        f"setp {sg}.steplen 5000\nsetp {sg}.stepspace 5000\nsetp {sg}.position-scale 1000\n"
        f"setp {sg}.maxaccel 0\nsetp {sg}.velocity-cmd 10\nstart\nloadusr -w sleep 0.6\n"
        f"getp {sg}.counts\nloadusr -w sleep 0.3\ngetp {sg}.counts\ngetp {PFX}.io_error\nstop\n"
    )
    r = run_hal(tmp_path, script, simclock=False)
    assert r.returncode == 0, r.stdout + r.stderr
    words = r.stdout.split()
    first, second, io_error = int(words[-3]), int(words[-2]), words[-1]
    assert 0 < first < second, r.stdout  # the board's time moves with the wall clock
    assert io_error == "FALSE"
