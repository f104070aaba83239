# SPDX-License-Identifier: GPL-2.0-or-later
"""waitlines.py FILE N [TIMEOUT_S]: wait until FILE has N lines (halsampler
writes its last rows after the HAL threads stopped); exit 1 on timeout."""

from __future__ import annotations

import sys
import time


def lines(path: str) -> int:
    try:
        with open(path, "rb") as f:
            return f.read().count(b"\n")
    except OSError:
        return 0


def main(argv: list[str]) -> int:
    path, n = argv[1], int(argv[2])
    deadline = time.monotonic() + (float(argv[3]) if len(argv) > 3 else 60.0)
    while lines(path) < n:
        if time.monotonic() > deadline:
            print(f"waitlines: {path} has {lines(path)} lines, want {n}", file=sys.stderr)
            return 1
        time.sleep(0.01)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
