# SPDX-License-Identifier: GPL-2.0-or-later
"""The fast board model (sim/verilator/fast) against the Verilated firmware.

vboard-fastdiff drives both models with the same random and directed bus and
pin stimulus and compares every register read and every pin edge with its
board time; the first difference fails with the operation, the board time and
the ClockLow cycle (docs/vboard.md "FAST MODEL").  Short runs here, 10^6
operations per module in bench/vboard/fastdiff.sh.  Then `vboard --model`:
which model runs a firmware, and the errors for a model that cannot."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
from vbhelpers import stop_clean, vboard

FASTDIFF = vboard.build_dir() / "bin" / "vboard-fastdiff"

# (board, firmware, module): every module of the firmwares the fast model covers.
CASES = [
    ("5i20", "SVST8_4", m)
    for m in ("idrom", "watchdog", "ioport", "led", "encoder", "stepgen", "pwmgen", "all")
] + [("5i20", "SV12", m) for m in ("encoder", "pwmgen", "all")]
# Encoder 0x83 (Probe, IndexMask pins) and StepGen 0x42 (swap bit)
CASES += [("5i20", "SV2ST2_PRB", m) for m in ("encoder", "stepgen", "all")]
# Every other local-bus firmware the fast model covers (auto runs them fast)
OTHERS = [
    ("5i20", "SVST2_4_7I47"),
    ("5i23", "SVST8_4"),
    ("4i65", "SVST8_4"),
    ("4i68", "SVST8_4"),
    ("5i22-1", "SVST8_8"),
    ("5i22-1", "SV16"),
    ("5i22-1.5", "SVST8_8"),
    ("3x20-1", "SV24"),
    ("3x20-1", "SVST16_24"),
]


def _fastdiff(*args: str, timeout: float = 300) -> subprocess.CompletedProcess[str]:
    assert FASTDIFF.exists(), f"{FASTDIFF} not built (make build)"
    return subprocess.run(
        [str(FASTDIFF), *args], capture_output=True, text=True, timeout=timeout, check=False
    )


@pytest.mark.parametrize("board,fw,module", CASES)
def test_fast_model_equals_rtl(board: str, fw: str, module: str) -> None:
    r = _fastdiff("--board", board, "--firmware", fw, "--module", module, "--ops", "1000")
    assert r.returncode == 0, r.stderr + r.stdout
    assert "models agree" in r.stdout
    # the run moved pins and let time pass in closed form, or it proved little
    edges = int(r.stdout.split(" reads, ")[1].split(" pin edges")[0])
    assert edges > 20, r.stdout
    skipped = int(r.stdout.split("skipped ")[1].split()[0])
    assert skipped > 0, r.stdout


@pytest.mark.parametrize("board,fw", OTHERS)
def test_fast_model_equals_rtl_other_boards(board: str, fw: str) -> None:
    r = _fastdiff("--board", board, "--firmware", fw, "--module", "all", "--ops", "500")
    assert r.returncode == 0, r.stderr + r.stdout
    assert "models agree" in r.stdout


def test_fastdiff_rejects_bad_arguments() -> None:
    r = _fastdiff("--board", "5i20", "--firmware", "SVST8_4", "--module", "nosuch")
    assert r.returncode != 0 and "unknown module 'nosuch'" in r.stderr
    r = _fastdiff("--board", "5i20", "--firmware", "NOPE")
    assert r.returncode != 0 and "no local-bus firmware 5i20/NOPE" in r.stderr


def _dump_refused(p: vboard.VBoardProcess, path: Path) -> bool:
    with p.client() as c:
        assert c.read(0x100, 1) == [0x55AACAFE]  # the IDROM cookie, either model
        try:
            c.dump(path)
        except vboard.VBoardError as e:
            assert "fast model has no waveforms" in e.message
            return True
        c.dump(None)
        return False


@pytest.mark.parametrize(
    "args,fast", [((), True), (("--model", "fast"), True), (("--model", "rtl"), False)]
)
def test_model_choice(sockdir: Path, args: tuple[str, ...], fast: bool) -> None:
    """The default for a covered firmware is the fast model; a dump tells them
    apart (only the RTL model has waveforms)."""
    p = vboard.VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4", list(args))
    try:
        assert _dump_refused(p, sockdir / "w.vcd") == fast
    finally:
        stop_clean(p)


def test_auto_runs_rtl_for_an_uncovered_firmware(sockdir: Path) -> None:
    p = vboard.VBoardProcess(sockdir / "b.sock", "5i25", "7I76x2")
    try:
        assert not _dump_refused(p, sockdir / "w.vcd")
    finally:
        stop_clean(p)


def test_dump_on_the_command_line_runs_rtl(sockdir: Path) -> None:
    p = vboard.VBoardProcess(sockdir / "b.sock", "5i20", "SVST8_4", ["--dump", "w.vcd"])
    try:
        with p.client() as c:
            c.advance(1_000)
    finally:
        stop_clean(p)
    assert "clk_low" in (sockdir / "w.vcd").read_text()


@pytest.mark.parametrize(
    "board,fw,args,text",
    [
        ("5i20", "SVST8_4", ["--model", "quick"], "bad --model 'quick': want rtl, fast or auto"),
        ("7i43", "SV8", ["--model", "fast"], "board 7i43 has no fast model"),
        # 7I76x2 carries Smart Serial, which the fast model does not cover
        (
            "5i25",
            "7I76x2",
            ["--model", "fast"],
            "--model fast: firmware 7I76x2 on 5i25: the fast model does not cover module SSerial",
        ),
    ],
)
def test_model_errors(sockdir: Path, board: str, fw: str, args: list[str], text: str) -> None:
    r = subprocess.run(
        [
            str(vboard.vboard_binary()),
            "--socket",
            str(sockdir / "b.sock"),
            "--board",
            board,
            "--firmware",
            fw,
            *args,
        ],
        capture_output=True,
        text=True,
        timeout=30,
        check=False,
    )
    assert r.returncode != 0 and text in r.stderr, r.stderr
