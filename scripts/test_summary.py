# SPDX-License-Identifier: GPL-2.0-or-later
"""The last lines of `make test`: outcome counts per area, and the verdict.

Inputs: ctest's JUnit file (the C unit tests), the skip guard's per-area JSON
(tests/common/skipguard.py --area-report), the two exit statuses.  Every
folder under tests/ holding a ``test_*.py`` is an expected area; one that ran
no passing test is reported as LOST and fails the run (unless the run was
narrowed with PYTEST_ARGS), as does a ctest test that was skipped or not run.
Exit status: 0 when everything passed, 1 otherwise.
"""

from __future__ import annotations

import argparse
import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

# Display names of the areas (folder under tests/ -> what it covers).
NAMES = {
    "cocotb": "HDL (cocotb)",
    "lint": "HDL lint",
    "hal": "HAL regression",
    "python": "HAL python",
    "driver": "driver",
    "vboard": "vboard",
    "e2e": "e2e",
    "tools": "tools",
    "docs": "docs examples",
    "fuzz": "fuzz",
    "infra": "test infra",
}
COLUMNS = ("passed", "failed", "errors", "skipped", "xfailed")


def expected_areas(tests: Path) -> list[str]:
    """Folders under tests/ that hold pytest files (each is one area)."""
    out = []
    for d in tests.iterdir():
        if d.is_dir() and d.name not in ("common", "data", "unit") and any(d.rglob("test_*.py")):
            out.append(d.name)
    order = list(NAMES)
    return sorted(out, key=lambda a: (order.index(a) if a in order else len(order), a))


def ctest_counts(junit: Path) -> dict[str, int]:
    """passed/failed/skipped of ctest's JUnit output (missing file: no tests)."""
    counts = {c: 0 for c in COLUMNS}
    if not junit.exists():
        counts["errors"] = 1
        return counts
    for case in ET.parse(junit).getroot().iter("testcase"):
        status = case.get("status", "")
        if status == "run":
            counts["passed"] += 1
        elif status == "fail":
            counts["failed"] += 1
        else:  # notrun, disabled, or ctest's skip return code
            counts["skipped"] += 1
    return counts


def row(name: str, c: dict[str, int], note: str = "") -> str:
    cells = "".join(f"{c.get(k, 0):>9d}" for k in COLUMNS)
    return f"  {name:<22s}{cells}  {note}".rstrip()


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--tests", type=Path, required=True, help="the tests/ folder")
    ap.add_argument("--ctest", type=Path, required=True, help="ctest --output-junit file")
    ap.add_argument("--areas", type=Path, required=True, help="skipguard --area-report file")
    ap.add_argument("--ctest-rc", type=int, required=True)
    ap.add_argument("--pytest-rc", type=int, required=True)
    ap.add_argument("--narrowed", action="store_true", help="pytest ran a subset (PYTEST_ARGS)")
    args = ap.parse_args(argv)

    problems: list[str] = []
    data = json.loads(args.areas.read_text()) if args.areas.exists() else {}
    areas: dict[str, dict[str, int]] = data.get("areas", {})
    if not data:
        problems.append("pytest wrote no area report (it did not run to the end)")

    print()
    print("=" * 30 + " make test: per area " + "=" * 30)
    print(f"  {'area':<22s}" + "".join(f"{k:>9s}" for k in COLUMNS))
    ct = ctest_counts(args.ctest)
    note = ""
    if ct["skipped"]:
        note = "NOT RUN"
        problems.append(f"ctest: {ct['skipped']} test(s) not run")
    if ct["passed"] == 0:
        note = "LOST"
        problems.append("ctest ran no C unit test")
    print(row("C units (ctest)", ct, note))

    names = expected_areas(args.tests)
    names += sorted(a for a in areas if a not in names)
    total = dict(ct)
    for a in names:
        c = areas.get(a, {})
        for k in COLUMNS:
            total[k] = total.get(k, 0) + c.get(k, 0)
        note = ""
        if not c.get("passed"):
            note = "no test ran" if args.narrowed else "LOST"
            if not args.narrowed:
                problems.append(f"area {a} (tests/{a}) ran no passing test")
        print(row(NAMES.get(a, a), c, note))
    print(row("total", total))

    pending = [p for p in data.get("pending", []) if p.get("xfailed")]
    if pending:
        print(f"  pending (tests/skips.txt): {sum(p['xfailed'] for p in pending)} test(s)")
    for u in data.get("unlisted", []):
        problems.append(f"unlisted skip: {u[0]}: {u[1]}")
    for s in data.get("stale", []):
        problems.append(f"stale allow-list entry: {s}")
    if args.ctest_rc:
        problems.append(f"ctest failed (exit {args.ctest_rc})")
    if args.pytest_rc:
        problems.append(f"pytest failed (exit {args.pytest_rc})")
    for p in problems:
        print(f"  FAIL: {p}")
    print("make test: " + ("FAILED" if problems else "ok"))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
