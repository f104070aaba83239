#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""check.py RESULT (via checkresult): every bad loadrt in cases.txt failed with a clear
message and left nothing behind.

LinuxCNC 2.9 accepts several of these (a bad cfg letter leaves a sampler
with no pins, extra depths or cfg strings are ignored, count=-1 loads
nothing): our rule is that any inconsistent module parameter fails the
load.  For each case: halrun exits 1, the module's error message contains
the text below, `show comp` lists only `not` (loaded first) and halcmd,
and `show pin` lists only the three pins of `not names=clash`.
"""
import re
import sys
from pathlib import Path

EXPECT = {
    "loadrt sampler": "SAMPLER: ERROR: no channels specified",
    "loadrt sampler cfg=bx depth=10": "unknown type 'x' at position 2",
    "loadrt sampler cfg=b depth=0": "channel 0 (cfg=b): depth missing or not positive (0)",
    "loadrt sampler cfg=b": "channel 0 (cfg=b): depth missing or not positive (0)",
    "loadrt sampler cfg=b,f depth=10": "channel 1 (cfg=f): depth missing or not positive",
    "loadrt sampler cfg=b depth=10,20": "depth given for channel 1 but only 1 cfg string(s)",
    "loadrt sampler cfg=fffffffffffffffffffffff depth=10": "more than 21 items",
    "loadrt sampler cfg=b depth=-5": "depth missing or not positive (-5)",
    "loadrt streamer cfg=q depth=4": "STREAMER: ERROR: channel 0: bad cfg 'q': unknown type 'q'",
    "loadrt streamer cfg=bf": "STREAMER: ERROR: channel 0 (cfg=bf): depth missing",
    "loadrt streamer cfg=b,s depth=4,0": "channel 1 (cfg=s): depth missing or not positive (0)",
    "loadrt and2 count=2 names=a,b": "count= and names= are mutually exclusive",
    "loadrt and2 names=a,a": 'and2: ERROR: names: "a" given twice',
    "loadrt and2 names=abcdefghijabcdefghijabcdefghijabcdefghijabcdefg": "too long",
    "loadrt and2 count=-1": "and2: ERROR: count=-1 out of range",
    "loadrt and2 count=5000": "and2: ERROR: count=5000 out of range",
    "loadrt siggen num_chan=17": "SIGGEN: ERROR: invalid number of channels: 17",
    "loadrt siggen num_chan=2 names=x,y": "num_chan= and names= are mutually exclusive",
    "loadrt or2 names=clash": "HAL: ERROR: duplicate variable 'clash.out'",
    "loadrt and2 names=a,,b": "names[1] is invalid (empty string)",
    "loadrt conv_float_s32 names=bad name": "Unknown parameter `name'",
}
PINS = ["clash.in", "clash.out", "clash.time"]

text = Path(sys.argv[1]).read_text()
blocks = re.split(r"^=== ", text, flags=re.M)[1:]
errors = []
seen = set()
for b in blocks:
    case, _, body = b.partition("\n")
    seen.add(case)
    lines = body.splitlines()
    want = EXPECT.get(case)
    if want is None:
        errors.append(f"unexpected case {case!r}")
        continue
    if not any(want in l for l in lines):
        errors.append(f"{case}: no message containing {want!r}")
    if lines[-1:] != ["exit 1"]:
        errors.append(f"{case}: halrun should fail, got {lines[-1:]}")
    comps = [l.split()[2] for l in lines if re.match(r"^\s+\d+\s+(RT|User)\s", l)]
    if sorted(c for c in comps if not c.startswith("halcmd")) != ["not"]:
        errors.append(f"{case}: components left: {comps}")
    pins = [l.split()[-1] for l in lines if re.match(r"^\s+\d+\s+(bit|float|s32|u32)\s", l)]
    if pins != PINS:
        errors.append(f"{case}: pins left: {pins}")
for missing in sorted(set(EXPECT) - seen):
    errors.append(f"case not run: {missing}")
for e in errors:
    print(e)
sys.exit(1 if errors else 0)
