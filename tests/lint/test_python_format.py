# SPDX-License-Identifier: GPL-2.0-or-later
"""Python is black-formatted with 100 columns (docs/engineering-standards.md).

Every Python file of the tree (tracked or new, not ignored) passes
``black --check --line-length 100`` with the black pinned in scripts/setup.sh,
except those listed in scripts/black-pending.txt (written before the check
existed); a listed file must exist and still need formatting, so the list
only shrinks.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PENDING = ROOT / "scripts" / "black-pending.txt"


def _black() -> str:
    exe = shutil.which("black") or str(Path(sys.executable).parent / "black")
    assert Path(exe).exists(), "black is not installed: run `make deps` (scripts/setup.sh)"
    return exe


def _pending() -> list[str]:
    lines = PENDING.read_text().splitlines()
    return [line.strip() for line in lines if line.strip() and not line.startswith("#")]


def _python_files() -> list[str]:
    r = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "*.py"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    )
    return [f for f in r.stdout.split() if (ROOT / f).is_file()]


def test_python_is_black_formatted() -> None:
    pending = set(_pending())
    files = [f for f in _python_files() if f not in pending]
    assert len(files) > 10, files
    r = subprocess.run(
        [_black(), "--check", "--line-length", "100", *files],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    bad = [line for line in r.stderr.splitlines() if line.startswith("would reformat")]
    assert r.returncode == 0, "run black --line-length 100 on:\n" + "\n".join(bad or [r.stderr])


def test_pending_list_only_holds_unformatted_files() -> None:
    stale = []
    for f in _pending():
        if not (ROOT / f).is_file():
            stale.append(f"{f}: no such file")
            continue
        r = subprocess.run(
            [_black(), "--check", "--quiet", "--line-length", "100", f],
            cwd=ROOT,
            capture_output=True,
        )
        if r.returncode == 0:
            stale.append(f"{f}: formatted now")
    assert not stale, "remove from scripts/black-pending.txt:\n" + "\n".join(stale)
