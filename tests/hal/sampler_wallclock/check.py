#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""check.py RESULT (via checkresult) for the wall-clock sampler/streamer run.

Rules (sampler(9)/halsampler(1)): the first 4 samples (numbers 0-3, values
1 2 3 3: the streamer holds its last value once empty) are kept; while the
FIFO is full new samples are dropped but still numbered, so halsampler
prints "overrun" before each sample whose number does not follow the
previous one, and nowhere else; sample-num counted every sample, so
sample-num = samples kept + overruns; the streamer underran in every
period after its 3 values, i.e. underruns = sample-num - 3 up to the
periods between the two functions' last runs (stop may fall between them).
"""
import sys
from pathlib import Path

lines = [l for l in Path(sys.argv[1]).read_text().split("\n") if l.strip()]
errors = []
if lines[-1] != "exit 0":
    errors.append(f"halrun failed: {lines[-1]}")
samples, marks = [], []
for l in lines[:-6]:
    if l == "overrun":
        marks.append(len(samples))
    else:
        n, v = l.split()
        samples.append((int(n), int(v)))
if len(samples) != 8:
    errors.append(f"want 8 samples, got {samples}")
if samples[:4] != [(0, 1), (1, 2), (2, 3), (3, 3)]:
    errors.append(f"first samples {samples[:4]}")
gaps = [i for i in range(1, len(samples)) if samples[i][0] != samples[i - 1][0] + 1]
if gaps != marks:
    errors.append(f"'overrun' lines before samples {marks}, gaps at {gaps}")
if not gaps or gaps[0] != 4:
    errors.append(f"expected the first gap after sample 3, gaps at {gaps}")
if any(samples[i][0] <= samples[i - 1][0] for i in range(1, len(samples))):
    errors.append("sample numbers not increasing")
try:
    overruns, sample_num = int(lines[-6]), int(lines[-5])
    full, underruns, empty = lines[-4], int(lines[-3]), lines[-2]
except ValueError:
    errors.append(f"bad getp output {lines[-6:]}")
else:
    if overruns < 50:
        errors.append(f"only {overruns} overruns in >100 ms at 1 kHz with depth 4")
    kept = sample_num - overruns
    if not 8 <= kept <= 8 + 4:
        errors.append(f"sample-num {sample_num} - overruns {overruns} = {kept} kept, "
                      "want 8 read + at most 4 queued")
    if abs(underruns - (sample_num - 3)) > 1:
        errors.append(f"underruns {underruns} vs sample-num {sample_num} - 3")
    if empty != "TRUE":
        errors.append(f"streamer.0.empty {empty}")
    if full not in ("TRUE", "FALSE"):
        errors.append(f"sampler.0.full {full}")
for e in errors:
    print(e)
sys.exit(1 if errors else 0)
