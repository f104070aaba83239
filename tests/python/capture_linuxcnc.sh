#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Dev tool (never run by `make test`): regenerate the `expected` file of
# h2's HAL regression-test folders from LinuxCNC 2.9, the behaviour
# reference.  Runs `halrun -f test.hal` of LinuxCNC in the folder (stdout
# and stderr merged, normalized by tests/hal/halnorm.py, as the runner
# compares them) and writes `expected`.
#   tests/python/capture_linuxcnc.sh tests/hal/and2 [tests/hal/or2 ...]
# Folders whose README says "expected: ours" are skipped: their expected
# output is our own specified behaviour, not LinuxCNC's.
here=$(cd "$(dirname "$0")" && pwd)
norm=$here/../hal/halnorm.py
[ -x /usr/bin/halrun ] || { echo "LinuxCNC halrun not installed"; exit 2; }
export RTAPI_UID=65534 RTAPI_FIFO_PATH=/tmp/.rtapi_fifo
for d in "$@"; do
    if grep -qs '^expected: ours' "$d/README"; then
        echo "skip $d (expected: ours)"
        continue
    fi
    (cd "$d" && PATH=/usr/bin:/bin timeout 60 /usr/bin/halrun -f test.hal > /tmp/h2cap.$$ 2>&1
     echo "$d: halrun exit $?"
     python3 "$norm" < /tmp/h2cap.$$ > expected)
done
rm -f /tmp/h2cap.$$
