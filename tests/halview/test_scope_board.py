# SPDX-License-Identifier: GPL-2.0-or-later
"""halscope --board: a HAL capture and the virtual board's firmware
waveforms in one VCD on the simulated time base.  Checked by counting the
hm2 stepgen's step pulses in the firmware's own output pin between two HAL
samples of the driver's step counter: they agree only when both are on one
time axis."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

from hvutil import BUILD, BUILT, ROOT, halrun, read_csv

sys.path.insert(0, str(ROOT / "tests" / "common"))
import vboard  # noqa: E402

pytestmark = pytest.mark.requires_build(*BUILT, BUILD / "bin" / "vboard")

HAL = """\
loadrt hostmot2
loadrt hm2_sim socket={sock} board=5i20 config="firmware=hm2/5i20/SVST8_4.BIT num_encoders=0 num_pwmgens=0 num_stepgens=1"
loadrt threads name1=servo period1=50000
addf hm2_5i20.0.read servo
addf hm2_5i20.0.write servo
setp hm2_5i20.0.stepgen.00.steplen 2000
setp hm2_5i20.0.stepgen.00.stepspace 2000
setp hm2_5i20.0.stepgen.00.position-scale 1000
setp hm2_5i20.0.stepgen.00.maxaccel 0
setp hm2_5i20.0.stepgen.00.control-type 1
setp hm2_5i20.0.stepgen.00.velocity-cmd 40
setp hm2_5i20.0.stepgen.00.enable 1
simrun 1ms
loadusr -Wn halscope halscope --thread servo -c hm2_5i20.0.stepgen.00.counts --samples 6 --position 0 --board {sock} --out merged.vcd --out hal.csv
simrun 1ms
waitusr halscope
"""
STEP_PIN = 48  # StepGen 0 Step on the 5i20 with SVST8_4 (its .PIN file)


def vcd_vector_changes(text: str, var: str, width: int) -> list[tuple[int, int]]:
    """(time, value) of the first top-level vector called `var`."""
    m = re.search(rf"\$var wire {width} (\S+) {var} \[{width - 1}:0\] \$end", text)
    assert m, var
    ident = re.escape(m.group(1))
    out, t = [], 0
    for line in text.splitlines():
        if line.startswith("#"):
            t = int(line[1:])
        elif re.fullmatch(rf"b([01xz]+) {ident}", line):
            bits = line.split()[0][1:].replace("x", "0").replace("z", "0")
            out.append((t, int(bits, 2)))
    return out


def test_capture_merged_with_firmware_dump(tmp_path: Path) -> None:
    sock = tmp_path / "vb.sock"
    # the firmware's waveforms come from the Verilated model (the fast model has none)
    with vboard.VBoardProcess(sock, "5i20", "SVST8_4", args=["--model", "rtl"]):
        r = halrun(tmp_path, HAL.format(sock=sock))
    assert r.returncode == 0, r.stderr
    assert not (tmp_path / "merged.vcd.board.vcd").exists(), "the board's own dump is removed"
    _, rows = read_csv(tmp_path / "hal.csv")
    counts = [int(r[2]) for r in rows]
    text = (tmp_path / "merged.vcd").read_text()
    m = re.match(r"\$comment .*HAL time \+ (-?\d+) ns = board time \$end", text)
    assert m
    offset = int(m.group(1))
    assert "$timescale 1ps $end" in text
    hal_var = re.search(r"\$var integer 32 (\S+) counts \$end", text)
    assert hal_var and "$scope module hal $end" in text
    # the HAL channel in the merged file: its changes at (HAL time + offset) in ps
    ident = re.escape(hal_var.group(1))
    hal_changes, t = [], 0
    for line in text.splitlines():
        if line.startswith("#"):
            t = int(line[1:])
        elif re.fullmatch(rf"b[01]+ {ident}", line):
            hal_changes.append((t, int(line.split()[0][1:], 2)))
    assert [v for _, v in hal_changes] == [
        c for i, c in enumerate(counts) if i == 0 or c != counts[i - 1]
    ]
    # HAL's samples are 50 us apart on the board's clock too
    sample_t = [t for t, _ in hal_changes]
    assert all((b - a) % 50_000_000 == 0 for a, b in zip(sample_t, sample_t[1:]))
    # step pulses on the firmware's pin between two HAL reads = the counter's change
    io_out = vcd_vector_changes(text, "io_out", 72)
    level, rises = 0, []
    for t, v in io_out:
        bit = (v >> STEP_PIN) & 1
        if bit and not level:
            rises.append(t)
        level = bit
    assert len(rises) >= 8, "40 kHz for 250 us"
    t0 = sample_t[0]
    for i in range(1, len(counts)):
        a, b = t0 + (i - 1) * 50_000_000, t0 + i * 50_000_000
        n = sum(1 for t in rises if a < t <= b)
        assert n == counts[i] - counts[i - 1], (i, n, counts)
    assert -2_000_000 < offset < 0, "the board started its epoch at the first period"
