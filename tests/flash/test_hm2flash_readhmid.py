# SPDX-License-Identifier: GPL-2.0-or-later
"""hm2flash --readhmid: the firmware listing (IDROM header, modules,
pin-out) in mesaflash's layout.

References: Debian's mesaflash --readhmid recorded against the same virtual
7i92 and 7i96S (tests/flash/data/mesaflash-*-readhmid.txt, made by
tests/flash/data/record.sh; re-record when those firmwares change), and for the
virtual 5i25 the firmware description hm2gen wrote (the .json beside the
.BIT), whose pin functions are the 7i92's: the rows must then be mesaflash's
7i92 rows.  hm2pinout --pin-file prints the same listing (one helper)."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

from ethboard import RECORDED_HMID, recorded_output, start_eth
from flashhelpers import StartBoard, run, vboard

PIN_LABEL_WIDTH = 18  # mesaflash's "%-18s" pin column; the rest is the same on every board


def rows(text: str) -> list[str]:
    """The pin-out rows without their pin label."""
    out = []
    for line in text.splitlines():
        if len(line) > PIN_LABEL_WIDTH + 10 and line[PIN_LABEL_WIDTH:].split()[1:2] == ["IOPort"]:
            out.append(line[PIN_LABEL_WIDTH:])
    return out


def test_7i92_matches_mesaflash_byte_for_byte(sockdir: Path) -> None:
    p, ip = start_eth(sockdir, "7i92")
    with p:
        r = run("--device", "7i92", "--addr", ip, "--readhmid")
    assert r.stdout == recorded_output("mesaflash-7i92-readhmid", RECORDED_HMID)


def test_7i96s_matches_mesaflash_but_for_pin_labels(sockdir: Path) -> None:
    p, ip = start_eth(sockdir, "7i96s")
    with p:
        r = run("--device", "7i96s", "--addr", ip, "--readhmid")
    want = recorded_output("mesaflash-7i96s-readhmid", RECORDED_HMID)
    head = want.index("Configuration pin-out:")
    assert r.stdout[:head] == want[:head]
    got_rows, want_rows = rows(r.stdout), rows(want)
    assert len(want_rows) == 51
    assert got_rows == want_rows
    # the labels are the driver's pin names (hostmot2's load log), e.g. TB1-02/TB1-03
    assert "TB1-02/TB1-03          17   IOPort       StepGen          0        Step/Table1" in (
        r.stdout
    )


def test_5i25_against_its_firmware_description(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    r = run("--device", "5i25", "--addr", f"sim:{sockdir / 'b.sock'}", "--readhmid")
    desc = json.loads(
        (vboard.build_dir() / "generated" / "5i25" / "7I76x2" / "7I76x2.json").read_text()
    )
    desc92 = json.loads(
        (vboard.build_dir() / "generated" / "7i92" / "7I76x2" / "7I76x2.json").read_text()
    )
    out = r.stdout
    assert out.startswith("Configuration Name: HOSTMOT2\n\nGeneral configuration information:")
    assert f"  BoardName : {desc['board']['idrom_name']}\n" in out
    assert f"  Clock Low frequency: {desc['clocks']['low_hz'] / 1e6:.4f} MHz\n" in out
    assert f"  IDROM Type: {desc['firmware']['idrom_type']}\n" in out
    for m in desc["modules"]:
        assert f"  BaseAddress: {m['base_address']:04X}\n" in out
        assert (
            f"in configuration\n  Version: {m['version']}\n  Registers: {m['registers']}\n" in out
        )
    assert out.count("  Module: ") == len(desc["modules"])
    # same pin functions as the 7i92's 7I76x2, so mesaflash's 7i92 rows
    fields = ("io", "sec_tag", "sec_unit", "sec_pin")
    assert [[p[k] for k in fields] for p in desc["pins"]] == [
        [p[k] for k in fields] for p in desc92["pins"]
    ]
    assert rows(out) == rows(recorded_output("mesaflash-7i92-readhmid", RECORDED_HMID))
    assert "IO Connections for P3\n" in out and "IO Connections for P2\n" in out


def test_hm2pinout_pin_file_is_the_same_listing(sockdir: Path, start_board: StartBoard) -> None:
    start_board()
    a = run("--device", "5i25", "--addr", f"sim:{sockdir / 'b.sock'}", "--readhmid")
    pinout = vboard.build_dir() / "bin" / "hm2pinout"
    b = subprocess.run(
        [str(pinout), "-p", f"sim:{sockdir / 'b.sock'}"], capture_output=True, text=True, timeout=60
    )
    assert b.returncode == 0, b.stderr
    assert b.stdout == a.stdout


def test_readhmid_errors(sockdir: Path) -> None:
    r = run("--device", "7i92", "--addr", "127.0.0.1", "--readhmid", "--reload", check=2)
    assert "give one command" in r.stderr
    # a blank virtual 5i25 (nothing in its flash): no firmware to list
    with vboard.VBoardProcess(
        sockdir / "b.sock", "5i25", None, args=["--flash", str(sockdir / "blank.bin")]
    ):
        r = run("--device", "5i25", "--addr", f"sim:{sockdir / 'b.sock'}", "--readhmid", check=1)
    assert "not configured (blank FPGA" in r.stderr
