# SPDX-License-Identifier: GPL-2.0-or-later
"""Resource and timing figures of the hm2 firmware tops (make bench).

* yosys ``synth_ice40 -noflatten`` (Debian yosys) of the 5i20 SVST8_4 and the
  7i43 SVST4_4 tops: LUT4 and flip-flop counts per module (one line per
  module type, with how many instances of it the top has, and the total);
* nextpnr-ice40 (HX8K) fmax of a stepgen + encoder + pwmgen slice, both
  clock domains, if nextpnr-ice40 is installed.

No Mesa figure is published for the iCE40, so there is no anchor: these are
the project's own numbers to watch for regressions.  ``baseline.json`` holds
the figures of an earlier commit (``--save-baseline`` writes it); each
module's line shows them beside the current ones."""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from hm2gen import load_firmware  # noqa: E402
from hm2gen.emit import write_all  # noqa: E402

HM2 = ROOT / "hdl" / "hostmot2"
TOPS = [("5i20", "SVST8_4"), ("7i43", "SVST4_4")]
LUT = "SB_LUT4"
FF = re.compile(r"^SB_DFF")


def sources(gen: Path, top: str) -> list[str]:
    return [
        str(gen / f"{top}.v"),
        *map(str, sorted(HM2.glob("hm2_*.v"))),
        *map(str, sorted((ROOT / "hdl" / "common").glob("*.v"))),
    ]


def synth(
    desc: Path, work: Path, boards: Path | None = None, flatten: bool = False
) -> tuple[dict, str, Path]:
    fw = load_firmware(desc, boards)
    gen = work / fw.board.name / fw.name
    write_all(fw, gen)
    top = fw.top_module
    out_json = work / f"{top}.json"
    script = (
        f"read_verilog -I{gen} {' '.join(sources(gen, top))}; "
        f"synth_ice40 -top {top} {'' if flatten else '-noflatten'} -json {out_json}; "
        "tee -o " + str(work / f"{top}.stat") + " stat"
    )
    r = subprocess.run(["yosys", "-q", "-p", script], capture_output=True, text=True)
    if r.returncode:
        raise SystemExit(f"yosys failed on {top}:\n{r.stdout[-3000:]}{r.stderr[-3000:]}")
    return json.loads(out_json.read_text()), top, out_json


def per_module(netlist: dict, top: str) -> tuple[dict[str, tuple[int, int]], Counter]:
    """Own LUT/FF cells of every module and the instance count of each in
    the hierarchy below ``top``."""
    mods = netlist["modules"]
    own: dict[str, tuple[int, int]] = {}
    children: dict[str, list[str]] = {}
    for name, m in mods.items():
        luts = ffs = 0
        kids = []
        for c in m["cells"].values():
            t = c["type"]
            if t == LUT:
                luts += 1
            elif FF.match(t):
                ffs += 1
            elif t in mods:
                kids.append(t)
        own[name] = (luts, ffs)
        children[name] = kids
    count: Counter = Counter()

    def walk(n: str) -> None:
        count[n] += 1
        for k in children[n]:
            walk(k)

    walk(top)
    return own, count


def family(name: str) -> str:
    """Module name without yosys' parameter suffix ($paramod$...\\hm2_x...)."""
    m = re.search(r"\\(\w+)", name)
    return m.group(1) if m else name


BASELINE = Path(__file__).resolve().parent / "baseline.json"


def report_top(desc: Path, work: Path, prev: dict[str, list[int]]) -> dict[str, list[int]]:
    netlist, top, _ = synth(desc, work)
    own, count = per_module(netlist, top)
    rows: dict[str, list[int]] = {}
    for name, n in count.items():
        if name.startswith("SB_"):  # iCE40 primitives (blackboxes)
            continue
        f = family(name)
        r = rows.setdefault(f, [0, 0, 0])
        r[0] += n
        r[1] += n * own[name][0]
        r[2] += n * own[name][1]
    print(f"{top}: yosys synth_ice40 -noflatten (LUT4 / FF, summed over instances)")
    print(f"  {'module':<22} {'inst':>4} {'LUT4':>6} {'FF':>6}   {'previous LUT4':>13} {'FF':>6}")
    tl = tf = pl = pf = 0

    def was(f: str) -> tuple[str, str]:
        if f not in prev:
            return "-", "-"
        return str(prev[f][1]), str(prev[f][2])

    for f, (n, lu, ff) in sorted(rows.items(), key=lambda kv: -kv[1][1]):
        pl_s, pf_s = was(f)
        print(f"  {f:<22} {n:>4} {lu:>6} {ff:>6}   {pl_s:>13} {pf_s:>6}")
        tl += lu
        tf += ff
    for f in prev:
        pl += prev[f][1]
        pf += prev[f][2]
    ptot = (str(pl), str(pf)) if prev else ("-", "-")
    print(f"  {'total':<22} {'':>4} {tl:>6} {tf:>6}   {ptot[0]:>13} {ptot[1]:>6}")
    return {f: list(r) for f, r in rows.items()}


def fmax_slice(work: Path) -> None:
    if not shutil.which("nextpnr-ice40"):
        raise SystemExit("bench/synth: nextpnr-ice40 is required (apt-get install nextpnr-ice40)")
    desc = work / "firmware" / "bench" / "SLICE.toml"
    desc.parent.mkdir(parents=True, exist_ok=True)
    desc.write_text((Path(__file__).parent / "slice.toml").read_text())
    _, top, nl = synth(desc, work, HM2 / "boards", flatten=True)
    r = subprocess.run(
        [
            "nextpnr-ice40",
            "--hx8k",
            "--package",
            "ct256",
            "--json",
            str(nl),
            "--freq",
            "100",
            "--seed",
            "1",
            "--timing-allow-fail",
        ],
        capture_output=True,
        text=True,
    )
    log = r.stdout + r.stderr
    if r.returncode:
        raise SystemExit(f"nextpnr-ice40 failed:\n{log[-3000:]}")
    found = re.findall(r"Max frequency for clock\s+'([^']+)': ([\d.]+) MHz", log)
    final: dict[str, str] = {}
    for clk, mhz in found:  # the last report (after routing) wins
        final[clk.split("$")[0]] = mhz
    util = re.findall(r"ICESTORM_LC:\s+(\d+)/\s*(\d+)", log)
    print(f"{top} (1 stepgen + 1 encoder + 1 pwmgen + core), nextpnr-ice40 HX8K ct256 seed 1:")
    if util:
        print(f"  logic cells: {util[-1][0]} / {util[-1][1]}")
    for clk, mhz in sorted(final.items()):
        print(f"  fmax {clk:<12} {mhz} MHz")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--keep", type=Path, help="keep the work files in this directory")
    ap.add_argument(
        "--save-baseline",
        metavar="LABEL",
        help="write this run's figures to baseline.json, labelled (e.g. a commit)",
    )
    ap.add_argument("--no-fmax", action="store_true", help="skip the nextpnr slice")
    args = ap.parse_args()
    base = json.loads(BASELINE.read_text()) if BASELINE.exists() else {"label": "", "tops": {}}
    if base["label"]:
        print(f"previous figures: {base['label']} (bench/synth/baseline.json)")
    figures: dict[str, dict[str, list[int]]] = {}
    if not shutil.which("yosys"):
        raise SystemExit("bench/synth: yosys is required (apt-get install yosys)")
    with tempfile.TemporaryDirectory() as tmp:
        work = args.keep or Path(tmp)
        work.mkdir(parents=True, exist_ok=True)
        for board, name in TOPS:
            desc = HM2 / "firmware" / board / f"{name}.toml"
            key = f"{board}/{name}"
            figures[key] = report_top(desc, work, base["tops"].get(key, {}))
            print()
        if not args.no_fmax:
            fmax_slice(work)
    if args.save_baseline:
        BASELINE.write_text(
            json.dumps({"label": args.save_baseline, "tops": figures}, indent=1) + "\n"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
