# SPDX-License-Identifier: GPL-2.0-or-later
"""Smart Serial end to end: the hostmot2 driver (sserial.c) through hm2_sim
against the 5i25 7I76x2 firmware's hm2_sserial.v and the virtual 7I76 of
the vboard (vboard --sserial), in halrun on the simulated clock.

References: the HAL names and directions of sserial(9) for a 7I76 (LinuxCNC
2.9's man page); the process-data scaling of docs/sserial.md (ADC LSB 0.01 V,
DAC 0..65535 = 0..spinout-scalemax), recomputed here; what the remote saw is
read back from the virtual 7I76 itself (VB_SSERIAL status)."""

from __future__ import annotations

import csv
import json
import re
import subprocess
from pathlib import Path
from typing import Iterator

import pytest
from hm2e2e import BUILD, PROBE, ROOT, halrun, needs_vboard, num, values
import sys
import vboard

pytestmark = needs_vboard

PFX = "hm2_5i25.0"
PINMAPS = ROOT / "tests" / "data" / "pinmaps"
R = f"{PFX}.7i76.0.0"
PORT = f"{PFX}.sserial.port-0"


def load(sock: Path, config: str = "sserial_port_0=2xxx", period_ns: int = 1_000_000) -> str:
    return (
        "loadrt hostmot2\n"
        f'loadrt hm2_sim socket={sock} board=5i25 config="{config}"\n'
        f"loadrt threads name1=servo period1={period_ns}\n"
        f"addf {PFX}.read servo\n"
        f"addf {PFX}.write servo\n"
    )


def ss(sock: Path, key: str, cmd: str) -> str:
    """A script line sending a VB_SSERIAL command (its JSON under %%key)."""
    return f"loadusr -w {sys.executable} {PROBE} {sock} sserial {key} {cmd}\n"


def remote(out: str, key: str) -> dict:
    v = values(out)
    assert key in v, f"{key} missing in:\n{out}"
    doc = json.loads(v[key][0])
    return doc["remotes"][0] if "remotes" in doc else doc


def tag_pins(name: str, *pins: str) -> str:
    out = f"loadusr -w echo @@{name}\n"
    return out + "".join(f"getp {p}\n" for p in pins)


@pytest.fixture
def board(tmp_path: Path) -> Iterator[Path]:
    sock = tmp_path / "ss.sock"
    with vboard.VBoardProcess(sock, "5i25", "7I76x2", ["--sserial", "0.0=7i76"]):
        yield sock


INPUTS = [f"{R}.input-{i:02d}" for i in range(32)]
INPUTS_NOT = [f"{R}.input-{i:02d}-not" for i in range(32)]


def setp_outputs(pattern: int) -> str:
    return "".join(f"setp {R}.output-{i:02d} {(pattern >> i) & 1}\n" for i in range(16))


def test_7i76_round_trip_inputs_outputs_spindle_analog(tmp_path: Path, board: Path) -> None:
    analog = [0.0, 1.5, 12.34, 36.0]
    script = load(board)
    for k, a in enumerate(analog):
        script += ss(board, f"a{k}", f"set 0.0 analog {k} {a}")
    script += ss(board, "f", "set 0.0 field 23.45")
    phases = [(0xA5A55A5A, 0x3C0F, 37.5, 1, 0), (0x5A5AA5A5, 0xC3F0, 250.0, 0, 1)]
    for n, (ins, outs, spin, ena, dirn) in enumerate(phases):
        script += ss(board, f"in{n}", f"set 0.0 inputs {ins:#x}")
        script += setp_outputs(outs)
        script += f"setp {R}.spinout {spin}\nsetp {R}.spinena {ena}\nsetp {R}.spindir {dirn}\n"
        script += "simrun 3ms\n"
        script += tag_pins(f"p{n}", *INPUTS, *INPUTS_NOT)
        script += tag_pins(f"an{n}", *[f"{R}.analogin{k}" for k in range(4)], f"{R}.fieldvoltage")
        script += ss(board, f"st{n}", "status")
    r = halrun(tmp_path, script)
    assert r.returncode == 0, r.stdout + r.stderr
    v = values(r.stdout + r.stderr)
    for n, (ins, outs, spin, ena, dirn) in enumerate(phases):
        for i in range(32):
            assert num(v, f"p{n}", i) == (ins >> i) & 1, f"phase {n} input-{i:02d}"
            assert num(v, f"p{n}", 32 + i) == 1 - ((ins >> i) & 1), f"phase {n} input-{i:02d}-not"
        for k, a in enumerate(analog):
            assert num(v, f"an{n}", k) == pytest.approx(round(a / 0.01) * 0.01, abs=1e-9)
        assert num(v, f"an{n}", 4) == pytest.approx(23.45, abs=1e-9)
        st = remote(r.stdout, f"st{n}")
        assert st["outputs"] == outs
        assert (st["spinena"], st["spindir"]) == (bool(ena), bool(dirn))
        # default spinout-scalemax 100, maxlim 100: 250 is clamped to full scale
        assert st["spinout_raw"] == round(min(spin, 100.0) / 100.0 * 65535)
        assert st["bad"] == 0


def test_one_doit_per_servo_period(tmp_path: Path, board: Path) -> None:
    script = load(board, period_ns=500_000) + "simrun 2ms\n"
    script += ss(board, "a", "status") + "simrun 20ms\n" + ss(board, "b", "status")
    script += tag_pins("err", f"{PORT}.error-count", f"{PORT}.run_state")
    r = halrun(tmp_path, script)
    assert r.returncode == 0, r.stdout + r.stderr
    a, b = remote(r.stdout, "a"), remote(r.stdout, "b")
    assert b["process"] - a["process"] == 40  # 20 ms / 0.5 ms
    assert b["bad"] == 0 and b["discovers"] == 1
    v = values(r.stdout)
    assert (num(v, "err", 0), num(v, "err", 1)) == (0, 3)


def test_cable_fault_stops_port_logs_and_run_toggle_restarts(tmp_path: Path, board: Path) -> None:
    script = load(board) + f"setp {PORT}.fault-lim 50\n"
    script += ss(board, "i1", "set 0.0 inputs 0x1") + "simrun 3ms\n"
    script += tag_pins("before", f"{R}.input-00", f"{PORT}.run_state", f"{PORT}.error-count")
    script += ss(board, "u", "set 0.0 plugged 0") + "simrun 10ms\n"
    script += tag_pins("fault", f"{PORT}.run_state", f"{PORT}.error-count")
    # plugged in again with new inputs: the port stays stopped, pins keep their values
    script += ss(board, "i2", "set 0.0 inputs 0x2") + ss(board, "p", "set 0.0 plugged 1")
    script += "simrun 5ms\n"
    script += tag_pins("still", f"{R}.input-00", f"{R}.input-01", f"{PORT}.run_state")
    script += f"setp {PORT}.run 0\nsimrun 2ms\n"
    script += tag_pins("off", f"{PORT}.run_state")
    script += f"setp {PORT}.run 1\nsimrun 5ms\n"
    script += tag_pins(
        "again", f"{R}.input-00", f"{R}.input-01", f"{PORT}.run_state", f"{PORT}.error-count"
    )
    r = halrun(tmp_path, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    v = values(out)
    assert [num(v, "before", i) for i in range(3)] == [1, 3, 0]
    assert num(v, "fault", 0) == 0
    assert num(v, "fault", 1) > 50
    assert re.search(
        r"hm2/hm2_5i25\.0: Smart Serial port 0 channel 0 \(7i76\): no answer \(remote unplugged"
        r".*error count \d+ > fault-lim 50: port 0 stopped",
        out,
    ), out
    assert [num(v, "still", i) for i in range(3)] == [1, 0, 0]
    assert num(v, "off", 0) == 0
    assert [num(v, "again", i) for i in range(4)] == [0, 1, 3, 0]


def test_no_remote_channel_and_gpio_channel(tmp_path: Path, board: Path) -> None:
    # channel 1 enabled but nothing on it; channels 2, 3 left to GPIO
    r = halrun(tmp_path, load(board, "sserial_port_0=00xx") + "show pin hm2_5i25.0.7i76\n")
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    assert "Smart Serial port 0 channel 0: found 7i76 (unit 0x76000000) in mode 0" in out
    assert f"{R}.input-00" in out and "hm2_5i25.0.7i76.0.1." not in out
    assert "IO Pin 012 (P3-09): Smart Serial Interface #0, pin tx1 (Output)" in out
    assert "IO Pin 027 (P2-07): IOPort" in out
    assert f"{R}.analogin0" not in out  # mode 0: no analog inputs (sserial(9))


@pytest.mark.parametrize(
    "cfg,msg",
    [
        ("sserial_port_0=0z", "channel mode must be 0..9 or x"),
        ("sserial_port_4=0", "port must be 0..3"),
        ("sserial_port_0=000000000", "1 to 8 channel modes expected"),
    ],
)
def test_bad_sserial_port_string_is_refused(
    tmp_path: Path, board: Path, cfg: str, msg: str
) -> None:
    r = halrun(tmp_path, load(board, cfg))
    out = r.stdout + r.stderr
    assert r.returncode != 0
    assert f'invalid token in config string: "{cfg}" ({msg})' in out, out
    assert f"{R}.input-00" not in out


def test_hm2pinout_lists_the_sserial_channels(board: Path) -> None:
    """Like mesaflash --readhmid: the SSerial module and every channel pin
    of Mesa's pin file (tests/data/pinmaps/PIN_7I76x2_34.csv)."""
    hm2pinout = BUILD / "bin" / "hm2pinout"
    rows = [
        r
        for r in csv.DictReader((PINMAPS / "PIN_7I76x2_34.csv").open())
        if r["sec_tag_name"] == "SSerial"
    ]
    assert len(rows) == 8
    r = subprocess.run(
        [str(hm2pinout), "-p", f"sim:{board}"], capture_output=True, text=True, timeout=60
    )
    assert r.returncode == 0, r.stderr
    assert re.search(r"Module: SSerial\n\s+There are 1 of SSerial in configuration", r.stdout)
    for row in rows:
        name = row["sec_pin_name"].replace("TxData", "TXData").replace("RxData", "RXData")
        d = "Out" if row["direction"] == "out" else "In"
        pat = rf"\s{row['io_pin']}\s+IOPort\s+SSerial\s+0\s+{name}\s+\({d}\)"
        assert re.search(pat, r.stdout), pat
    r = subprocess.run(
        [str(hm2pinout), "-s", "-c", "sserial_port_0=00x0", f"sim:{board}"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert r.returncode == 0, r.stderr
    for row in rows:
        k = int(row["sec_pin_name"][-1])
        io = int(row["io_pin"])
        if k == 2:
            assert re.search(rf"IO Pin {io:03d} \(P\d-\d\d\): IOPort", r.stdout)
        else:
            kind = "tx" if row["direction"] == "out" else "rx"
            d = "Output" if row["direction"] == "out" else "Input"
            want = f"IO Pin {io:03d} (P"
            line = next(x for x in r.stdout.splitlines() if want in x)
            assert line.endswith(f"Smart Serial Interface #0, pin {kind}{k} ({d})"), line


def test_7i77_io_and_analog_servo_outputs(tmp_path: Path) -> None:
    """A 7I77 on channels 0 (field I/O, the 7I76's pins) and 1 (six analog
    outputs, sserial(9) names): values reach the virtual 7I77 scaled as
    docs/sserial.md says (clamp to min/maxlim, +-scalemax = +-16383)."""
    sock = tmp_path / "s77.sock"
    r77 = f"{PFX}.7i77.0"
    outs = [2.5, -10.0, 12.0, 0.0, -3.3, 7.0]  # 12 V is past maxlim 10: clamped
    script = load(sock, "sserial_port_0=00xx")
    script += ss(sock, "i", "set 0.0 inputs 0x80000001")
    script += f"setp {r77}.0.output-15 1\nsetp {r77}.1.analogena 1\n"
    script += f"setp {r77}.1.analogout5-scalemax 14\nsetp {r77}.1.analogout4-minlim -2\n"
    script += "".join(f"setp {r77}.1.analogout{k} {v}\n" for k, v in enumerate(outs))
    script += "simrun 3ms\n" + tag_pins("in", f"{r77}.0.input-00", f"{r77}.0.input-31")
    script += ss(sock, "st", "status")
    with vboard.VBoardProcess(sock, "5i25", "7I76x2", ["--sserial", "0.0=7i77"]):
        r = halrun(tmp_path, script)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out
    v = values(out)
    assert (num(v, "in", 0), num(v, "in", 1)) == (1, 1)
    remotes = json.loads(values(r.stdout)["st"][0])["remotes"]
    io = next(x for x in remotes if x["channel"] == "0.0")
    an = next(x for x in remotes if x["channel"] == "0.1")
    assert (io["type"], io["outputs"]) == ("7i77", 0x8000)
    assert an["analogena"] is True
    scale = [10.0] * 5 + [14.0]
    lim = [(-10.0, 10.0)] * 4 + [(-2.0, 10.0), (-10.0, 10.0)]
    want = [round(min(max(x, lo), hi) / s * 16383) for x, s, (lo, hi) in zip(outs, scale, lim)]
    assert an["analogout_raw"] == want
    assert an["process"] == io["process"] > 0
    assert "Smart Serial port 0 channel 1: found 7i77" in out
