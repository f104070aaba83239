# SPDX-License-Identifier: GPL-2.0-or-later
"""Build the halcmd line-parser libFuzzer target with clang and run it for a
few seconds.  clang and its libFuzzer runtime are required (scripts/setup.sh
installs clang and libclang-rt-14-dev): without them the test fails."""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "tests" / "fuzz" / "fuzz_halcmd_parse.c"
PARSER = ROOT / "host" / "hal" / "halcmd" / "halcmd_parse.c"
SECONDS = int(os.environ.get("HM_FUZZ_SECONDS", "5"))


def _build(tmp: Path) -> Path:
    clang = shutil.which("clang")
    assert clang is not None, "clang not installed (sudo apt-get install clang, or: make deps)"
    exe = tmp / "fuzz_halcmd_parse"
    proc = subprocess.run(
        [clang, "-g", "-O1", "-fsanitize=fuzzer,address,undefined",
         f"-I{PARSER.parent}", str(SRC), str(PARSER), "-o", str(exe)],
        capture_output=True, text=True,
    )
    if proc.returncode != 0:
        pytest.fail(f"fuzz target did not build:\n{proc.stderr}")
    return exe


def test_fuzz_halcmd_parser(tmp_path: Path) -> None:
    exe = _build(tmp_path)
    corpus = tmp_path / "corpus"
    corpus.mkdir()
    seeds = [
        "net a and2.0.out => and2.0.in0 # c",
        "setp x [AXIS_0]SCALE",
        "newsig $HOME$(PATH) float",
        'print "a b" \\',
        "loadrt threads name1=t period1=1000000",
    ]
    for i, s in enumerate(seeds):
        (corpus / f"seed{i}").write_text(s)
    proc = subprocess.run(
        [str(exe), f"-max_total_time={SECONDS}", "-max_len=512", "-rss_limit_mb=1024",
         str(corpus)],
        capture_output=True, text=True, cwd=tmp_path, timeout=SECONDS + 120,
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "Done" in proc.stderr or "DONE" in proc.stderr, proc.stderr[-2000:]
