# SPDX-License-Identifier: GPL-2.0-or-later
"""The halcmd input-handling libFuzzer target (tests/fuzz/fuzz_halcmd_parse.c).

Built with clang (a required tool: a missing clang or libFuzzer runtime fails
the test).  Every input of the kept corpus (tests/fuzz/corpus/halcmd) is
replayed first, then the fuzzer runs for HM_FUZZ_SECONDS (5 s in `make test`,
longer in `make fuzz`) on a copy of the corpus, so new inputs never land in
the tree.  A crash input is copied to tests/fuzz/crashes/ for inspection.
"""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "tests" / "fuzz" / "fuzz_halcmd_parse.c"
PARSER = ROOT / "host" / "hal" / "halcmd" / "halcmd_parse.c"
CORPUS = ROOT / "tests" / "fuzz" / "corpus" / "halcmd"
SECONDS = int(os.environ.get("HM_FUZZ_SECONDS", "5"))


def _build(tmp: Path) -> Path:
    clang = shutil.which("clang")
    assert clang is not None, "clang not installed (sudo apt-get install clang, or: make deps)"
    exe = tmp / "fuzz_halcmd_parse"
    proc = subprocess.run(
        [
            clang,
            "-g",
            "-O1",
            "-fsanitize=fuzzer,address,undefined",
            "-fno-sanitize-recover=undefined",
            f"-I{PARSER.parent}",
            str(SRC),
            str(PARSER),
            "-o",
            str(exe),
        ],
        capture_output=True,
        text=True,
    )
    assert proc.returncode == 0, f"fuzz target did not build:\n{proc.stderr}"
    return exe


def test_fuzz_corpus_replay(tmp_path: Path) -> None:
    exe = _build(tmp_path)
    inputs = sorted(p for p in CORPUS.iterdir() if p.is_file())
    assert len(inputs) >= 5, f"corpus {CORPUS} is missing"
    proc = subprocess.run(
        [str(exe), *map(str, inputs)], capture_output=True, text=True, cwd=tmp_path, timeout=120
    )
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert proc.stderr.count("Executed ") == len(inputs), proc.stderr[-2000:]


def test_fuzz_halcmd_parser(tmp_path: Path) -> None:
    exe = _build(tmp_path)
    corpus = tmp_path / "corpus"
    shutil.copytree(CORPUS, corpus)
    proc = subprocess.run(
        [
            str(exe),
            f"-max_total_time={SECONDS}",
            "-max_len=4096",
            "-rss_limit_mb=1024",
            f"-artifact_prefix={tmp_path}/",
            str(corpus),
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=SECONDS + 120,
    )
    if proc.returncode != 0:
        keep = ROOT / "tests" / "fuzz" / "crashes"
        keep.mkdir(exist_ok=True)
        for crash in tmp_path.glob("crash-*"):
            shutil.copy(crash, keep / crash.name)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert "Done" in proc.stderr or "DONE" in proc.stderr, proc.stderr[-2000:]
