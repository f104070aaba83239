#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""check.py RESULT (via checkresult): compare with `expected` after normalizing process
ids (halcmd<pid> names and the PID column of `show comp`, as the runner's
normalization does, and the pid in halsampler's "in use by process N")."""
import re
import sys
from pathlib import Path

here = Path(__file__).resolve().parent
text = Path(sys.argv[1]).read_text()
text = re.sub(r"in use by process \d+", "in use by process PID", text)
text = re.sub(r"halcmd\d+", "halcmdPID", text)
text = re.sub(r"^( +\d+  User  \S+) +\d+ (ready|initializing)$", r"\1 PID \2", text,
              flags=re.M)
got = text
want = (here / "expected").read_text()
if got != want:
    import difflib
    sys.stdout.writelines(difflib.unified_diff(want.splitlines(True), got.splitlines(True),
                                               "expected", "result"))
    sys.exit(1)
