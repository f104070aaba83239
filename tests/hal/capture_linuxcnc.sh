#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Dev tool (never run by `make test`): record the `expected` file of HAL
# regression-test folders from LinuxCNC 2.9, the behaviour reference.
# Runs LinuxCNC's halrun through lcnc-halrun (which serializes LinuxCNC
# sessions) with the folder's halrun.args on test.hal, stdout and stderr
# merged, normalized by halnorm.py as the runner compares them, and writes
# `expected`.
#   tests/hal/capture_linuxcnc.sh tests/hal/and2 [tests/hal/or2 ...]
# Folders whose README says "expected: ours" are skipped: their expected
# output is our own specified behaviour, not LinuxCNC's.
here=$(cd "$(dirname "$0")" && pwd)
command -v lcnc-halrun > /dev/null || { echo "lcnc-halrun (LinuxCNC 2.9) not installed"; exit 2; }
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
for d in "$@"; do
    if grep -qs '^expected: ours' "$d/README"; then
        echo "skip $d (expected: ours)"
        continue
    fi
    args=()
    [ -f "$d/halrun.args" ] && read -r -a args < "$d/halrun.args"
    (cd "$d" && PATH=/usr/local/bin:/usr/bin:/bin timeout 600 lcnc-halrun "${args[@]}" -f test.hal \
        > "$tmp" 2>&1
     echo "$d: halrun exit $?"
     grep -v "^Running with fallback_uid\|^Note: Using POSIX" "$tmp" | python3 "$here/halnorm.py" > expected)
done
