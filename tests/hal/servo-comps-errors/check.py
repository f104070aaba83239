#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""check.py RESULT (via checkresult): every bad loadrt in cases.txt failed
with the message below (LinuxCNC 2.9's text where 2.9 has one) and left
nothing behind; the maxvel message came once per channel and maxvel was
lowered to what the timing allows (500 steps/s for step/dir with 1 ms
steplen and stepspace, 1000 for quadrature: 333.3333 units/s at scale 3)."""

import re
import sys
from pathlib import Path

EXPECT = {
    "loadrt pid num_chan=17": "PID: ERROR: invalid number of channels: 17",
    "loadrt pid num_chan=-1": "PID: ERROR: invalid number of channels: -1",
    "loadrt pid num_chan=2 names=a": "num_chan= and names= are mutually exclusive",
    "loadrt pid names=a,a": 'pid: ERROR: names: "a" given twice',
    "loadrt pid debug=x": "`x' invalid for parameter `debug=x'",
    "loadrt stepgen": "STEPGEN: ERROR: no channels configured",
    "loadrt stepgen step_type=-1": "STEPGEN: ERROR: no channels configured",
    "loadrt stepgen step_type=16": "STEPGEN: ERROR: bad stepping type '16', axis 0",
    "loadrt stepgen step_type=0,1 ctrl_type=p,x": (
        "STEPGEN: ERROR: bad control type 'x' for axis 1 (must be 'p' or 'v')"
    ),
    "loadrt stepgen step_type=15 user_step_type=1,32": (
        "STEPGEN: ERROR: bad user step type uses more than 5 phases"
    ),
    "loadrt stepgen step_type=15 user_step_type=-5,1": (
        "STEPGEN: ERROR: bad user step type uses more than 5 phases"
    ),
    "loadrt stepgen step_type=0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0": "(at most 16)",
    "loadrt stepgen step_type=15 user_step_type=1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1,1": (
        "(at most 18)"
    ),
    "loadrt encoder num_chan=9": "ENCODER: ERROR: invalid number of channels: 9",
    "loadrt encoder num_chan=-1": "ENCODER: ERROR: invalid number of channels: -1",
    "loadrt encoder num_chan=2 names=a,b": "num_chan= and names= are mutually exclusive",
    "loadrt encoder names=a,b,c,d,e,f,g,h,i": "(at most 8)",
    "loadrt pwmgen": "PWMGEN: ERROR: no channels configured",
    "loadrt pwmgen output_type=-1": "PWMGEN: ERROR: no channels configured",
    "loadrt pwmgen output_type=1,3": "PWMGEN: ERROR: bad output type '3', channel 1",
    "loadrt pwmgen output_type=0,0,0,0,0,0,0,0,0": "(at most 8)",
    "loadrt pwmgen output_type=x": "`x' invalid for parameter `output_type=x'",
    "loadrt steptest count=2 names=a": "count= and names= are mutually exclusive",
}
MAXVEL = [
    "STEPGEN: Channel 0: The requested maximum velocity of 2000 steps/sec is too high.",
    "STEPGEN: The maximum possible frequency is 500 steps/second",
    "STEPGEN: Channel 1: The requested maximum velocity of 3000 steps/sec is too high.",
    "STEPGEN: The maximum possible frequency is 1000 steps/second",
    "500",
    "333.3333",
    "exit 0",
]

text = Path(sys.argv[1]).read_text()
blocks = re.split(r"^=== ", text, flags=re.M)[1:]
errors = []
seen = set()
for b in blocks:
    case, _, body = b.partition("\n")
    seen.add(case)
    lines = body.splitlines()
    if case == "maxvel":
        # messages from the realtime thread and halcmd's getp interleave freely
        if sorted(lines) != sorted(MAXVEL):
            errors.append(f"maxvel session printed {lines}, want {MAXVEL}")
        continue
    want = EXPECT.get(case)
    if want is None:
        errors.append(f"unexpected case {case!r}")
        continue
    if not any(want in line for line in lines):
        errors.append(f"{case}: no message containing {want!r}: {lines}")
    if lines[-1:] != ["exit 1"]:
        errors.append(f"{case}: halrun should fail, got {lines[-1:]}")
    comps = [line.split()[2] for line in lines if re.match(r"^\s+\d+\s+(RT|User)\s", line)]
    if any(not c.startswith("halcmd") for c in comps):
        errors.append(f"{case}: components left: {comps}")
    if any(re.match(r"^\s+\d+\s+(bit|float|s32|u32)\s", line) for line in lines):
        errors.append(f"{case}: pins left")
for missing in sorted((set(EXPECT) | {"maxvel"}) - seen):
    errors.append(f"case not run: {missing}")
for e in errors:
    print(e)
sys.exit(1 if errors else 0)
