#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""check.py RESULT (via checkresult): the simulated-clock sampler/streamer run was lossless.

Model: sample k (k = 0..999) carries line k of in.txt, printed by
halsampler as "k s f " with f as "%f"; 2000 periods ran (simrun 2s at
1 ms), so the streamer underran exactly 2000 - 1000 times once halstreamer
had left, and the sampler, after halsampler left with 1000 samples read and
4 more in its FIFO, overran exactly 2000 - 1004 times; sample-num counted
all 2000 samples.
"""
import sys
from pathlib import Path

here = Path(__file__).resolve().parent
session, _, sampled = Path(sys.argv[1]).read_text().partition("--- out.txt\n")
result = session.split("\n")
errors = []
want = []
for k, line in enumerate((here / "in.txt").read_text().splitlines()):
    s, f = line.split()
    want.append("%d %d %f " % (k, int(s), float(f)))
got = sampled.split("\n")[:-1]
if got != want:
    bad = next((i for i, (g, w) in enumerate(zip(got, want)) if g != w), min(len(got), len(want)))
    errors.append(f"out.txt differs from the model at line {bad} "
                  f"(got {len(got)} lines): {got[bad:bad+1]} vs {want[bad:bad+1]}")
tail = [l for l in result if l.strip()]
if tail[-4:] != ["996", "2000", "1000", "exit 0"]:
    errors.append(f"counters/exit: got {tail[-4:]}, want ['996', '2000', '1000', 'exit 0']")
for e in errors:
    print(e)
sys.exit(1 if errors else 0)
