# SPDX-License-Identifier: GPL-2.0-or-later
"""halscope --merge FILE.vcd --board-offset NS: a capture merged into a
waveform dump made some other way (a board's `vboard --dump`, here one
written by hand so every time is known).  The board's changes stay as they
were; the HAL channel's changes appear at board time = HAL time + offset,
in the dump's unit (ps), interleaved in time order (GTKWave's loader reads
the result).  Bad merge options change nothing in HAL."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from hvutil import BUILT, halrun, parse_vcd

VCD2FST, FST2VCD = "/usr/bin/vcd2fst", "/usr/bin/fst2vcd"
pytestmark = pytest.mark.requires_build(*BUILT, VCD2FST, FST2VCD)

US = 1_000_000  # ps
BOARD = f"""\
$date today $end
$timescale 1ps $end
$scope module top $end
$var wire 1 ! clk $end
$var wire 4 " bus [3:0] $end
$upscope $end
$enddefinitions $end
#0
$dumpvars
0!
b0000 "
$end
#{150 * US}
1!
#{250 * US}
b0101 "
#{1000 * US}
0!
"""
# records at HAL times 100, 200 (x = 0), 300, 400 (x = 7), 500 us (x = -3)
HAL = """\
loadrt threads name1=fast period1=100000
newsig x s32
loadusr -Wn halscope halscope --thread fast -c x --mode roll --duration 500us {args} -q
simrun 200us
sets x 7
simrun 200us
sets x -3
simrun 100us
waitusr halscope
"""


def s32(v: int) -> str:
    return "b" + format(v & 0xFFFFFFFF, "032b")


def test_merge_into_a_dump(tmp_path: Path) -> None:
    (tmp_path / "board.vcd").write_text(BOARD)
    args = "--merge board.vcd --board-offset -50000 -o merged.vcd"
    r = halrun(tmp_path, HAL.format(args=args))
    assert r.returncode == 0, r.stderr
    text = (tmp_path / "merged.vcd").read_text()
    assert text.startswith("$comment") and "HAL time + -50000 ns = board time" in text
    stamps = [int(line[1:]) for line in text.splitlines() if line.startswith("#")]
    assert stamps == sorted(set(stamps)), "one time stamp each, in order"
    fst = tmp_path / "m.fst"
    subprocess.run([VCD2FST, str(tmp_path / "merged.vcd"), str(fst)], check=True)
    got = parse_vcd(
        subprocess.run([FST2VCD, str(fst)], check=True, capture_output=True, text=True).stdout
    )
    assert got["clk"] == [(0, "0"), (150 * US, "1"), (1000 * US, "0")]
    assert got["bus"] == [(0, "b0000"), (250 * US, "b0101")]
    # HAL time 100 us - 50 us = 50 us on the board; 300 -> 250; 500 -> 450
    assert got["x"] == [(50 * US, s32(0)), (250 * US, s32(7)), (450 * US, s32(-3))]


@pytest.mark.parametrize(
    "args,message",
    [
        ("--merge nothere.vcd --board-offset 0 -o m.vcd", "cannot read the board's dump"),
        ("--merge notvcd.txt --board-offset 0 -o m.vcd", "not a VCD file"),
        ("--merge board.vcd -o m.vcd", "--merge needs --board-offset NS"),
        ("--merge board.vcd --board-offset 1.5 -o m.vcd", "--board-offset '1.5': a whole number"),
        ("--merge board.vcd --board-offset 0 -o m.csv", "into a .vcd output: name one"),
        ("--merge coarse.vcd --board-offset 0 -o m.vcd", "time unit 10us is coarser than 1 ns"),
    ],
)
def test_bad_merge_changes_nothing(tmp_path: Path, args: str, message: str) -> None:
    (tmp_path / "board.vcd").write_text(BOARD)
    (tmp_path / "notvcd.txt").write_text("hello\n")
    (tmp_path / "coarse.vcd").write_text(BOARD.replace("1ps", "10us"))
    hal = HAL.format(args=args).replace("loadusr -Wn", "loadusr -w").split("simrun")[0]
    r = halrun(tmp_path, hal + "show comp\nshow thread\n")
    assert message in r.stderr, r.stderr
    assert "scope_rt" not in r.stdout and "scope.sample" not in r.stdout
    assert not list(tmp_path.glob("m.*"))
