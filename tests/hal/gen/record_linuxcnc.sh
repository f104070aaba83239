#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Dev tool (never run by `make test`): record the `expected` output of HAL
# regression folders from LinuxCNC 2.9, the behaviour reference.  Runs
# LinuxCNC's halrun through lcnc-halrun (which serializes sessions) in a
# private IPC/PID namespace (so a stale rtapi_app of another session does not
# look like a running LinuxCNC), normalizes stdout with ../halnorm.py and
# writes `expected`; stderr goes to `expected.stderr` when the folder has one.
#   tests/hal/gen/record_linuxcnc.sh tests/hal/limit3-track [...]
here=$(cd "$(dirname "$0")" && pwd)
norm=$here/../halnorm.py
lcnc=$(command -v lcnc-halrun) || { echo "lcnc-halrun not installed"; exit 2; }
for d in "$@"; do
    args=()
    [ -f "$d/halrun.args" ] && read -r -a args < "$d/halrun.args"
    # -S (our simulated clock) has no LinuxCNC counterpart
    args=("${args[@]/-S/}")
    (cd "$d" && PATH=/usr/bin:/bin timeout 300 unshare --pid --fork --mount-proc --ipc \
        "$lcnc" ${args[@]} -f test.hal > /tmp/rec.out.$$ 2> /tmp/rec.err.$$
     echo "$d: halrun exit $?"
     python3 "$norm" < /tmp/rec.out.$$ > expected
     if [ -f expected.stderr ]; then
         grep -v -e '^Running with fallback_uid' -e '^Note: Using POSIX' /tmp/rec.err.$$ |
             python3 "$norm" > expected.stderr
     fi)
done
rm -f /tmp/rec.out.$$ /tmp/rec.err.$$
