# SPDX-License-Identifier: GPL-2.0-or-later
"""Size of the Pluto-P firmwares (make bench): does pluto_servo / pluto_step
fit the board's ACEX EP1K10 (576 logic elements)?

* yosys 0.23 ``synth_ice40`` (flattened) of each top: SB_LUT4, flip-flops
  (every SB_DFF* cell) and SB_CARRY, beside the figures of LinuxCNC's
  original Pluto Verilog under the same run (issue 14; that source is not
  on this machine, so the anchor is the recorded figure);
* an EP1K10 logic-element estimate: the iCE40 logic-cell count after
  nextpnr-ice40 packing.  An iCE40 logic cell and an ACEX 1K logic element
  both hold one LUT4, one flip-flop fed by it and one carry-chain bit, so
  the packed count is a fair stand-in (Quartus may pack differently);
* fmax of each top placed and routed on an iCE40 HX1K (the firmware runs
  at 40 MHz)."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PLUTO = ROOT / "hdl" / "pluto"
EP1K10_LE = 576
# LinuxCNC's original pluto_servo / pluto_step Verilog, yosys 0.23
# synth_ice40 (issue 14): LUT4, FF, carry.  The issue gives this project's
# pre-reduction firmwares as 494 / 726 / 165 and 448 / 682 / 113 in the same
# breath, and their flip-flop counts measured here are 363 and 341, half
# of those: the original's flip-flop figures may be doubled the same way,
# so both readings are printed.
ORIGINAL = {"pluto_servo": (457, 580, 165), "pluto_step": (352, 508, 105)}


def yosys_counts(top: str, work: Path) -> tuple[dict[str, int], Path]:
    out = work / f"{top}.json"
    srcs = " ".join(str(p) for p in sorted(PLUTO.glob("*.v")))
    script = f"read_verilog {srcs}; synth_ice40 -top {top} -json {out}; stat"
    r = subprocess.run(["yosys", "-p", script], capture_output=True, text=True)
    if r.returncode:
        raise SystemExit(f"yosys failed on {top}:\n{r.stdout[-3000:]}{r.stderr[-3000:]}")
    stat = r.stdout[r.stdout.rfind("Printing statistics") :]
    counts = {"lut": 0, "ff": 0, "carry": 0}
    for cell, n in re.findall(r"^\s+(SB_\w+)\s+(\d+)$", stat, re.M):
        if cell == "SB_LUT4":
            counts["lut"] += int(n)
        elif cell.startswith("SB_DFF"):
            counts["ff"] += int(n)
        elif cell == "SB_CARRY":
            counts["carry"] += int(n)
    return counts, out


def place(netlist: Path) -> tuple[int | None, float | None]:
    """Packed logic cells and routed fmax on an HX1K (None: not in the log)."""
    args = ["nextpnr-ice40", "--hx1k", "--package", "tq144", "--json", str(netlist)]
    args += ["--freq", "40", "--seed", "1", "--timing-allow-fail"]
    r = subprocess.run(args, capture_output=True, text=True)
    log = r.stdout + r.stderr
    if r.returncode:
        raise SystemExit(f"nextpnr-ice40 failed on {netlist.name}:\n{log[-3000:]}")
    lc = re.findall(r"ICESTORM_LC:\s+(\d+)/", log)
    mhz = re.findall(r"Max frequency for clock\s+'[^']+': ([\d.]+) MHz", log)
    return (int(lc[-1]) if lc else None), (float(mhz[-1]) if mhz else None)


def main() -> int:
    for tool in ("yosys", "nextpnr-ice40"):
        if not shutil.which(tool):
            raise SystemExit(f"bench/synth: {tool} is required (apt-get install {tool})")
    print(
        "Pluto-P firmwares, yosys synth_ice40 (flat); EP1K10 = "
        f"{EP1K10_LE} logic elements; anchor = LinuxCNC's original Verilog"
    )
    print(
        f"  {'top':12} {'LUT4':>5} {'FF':>4} {'carry':>5} {'LE est.':>7} {'fmax':>10}"
        f"   anchor LUT4 / FF / carry      LUT4 x   FF x (FF/2 x)"
    )
    with tempfile.TemporaryDirectory() as tmp:
        for top, (alut, aff, acarry) in ORIGINAL.items():
            c, netlist = yosys_counts(top, Path(tmp))
            lc, mhz = place(netlist)
            les = "-" if lc is None else f"{lc}"
            fmax = "-" if mhz is None else f"{mhz:.0f} MHz"
            print(
                f"  {top:12} {c['lut']:>5} {c['ff']:>4} {c['carry']:>5} {les:>7} {fmax:>10}"
                f"   {alut:>4} / {aff:>3} / {acarry:>3}"
                f"        {c['lut'] / alut:5.2f}  {c['ff'] / aff:5.2f}"
                f"  ({c['ff'] / (aff / 2):4.2f})"
            )
            if lc is not None and lc > EP1K10_LE:
                print(f"  !! {top}: {lc} logic cells > {EP1K10_LE} (EP1K10)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
