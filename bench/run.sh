#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make bench`: every speed figure of the project, each printed next to its
# anchor (LinuxCNC 2.9 measured on this machine when installed, or the
# published figure).  Not part of `make test`.  Each area keeps its own
# bench/<area>/run.sh, runnable on its own; this script runs them in turn and
# keeps going when one fails, so one broken bench does not hide the others.
set -uo pipefail
cd "$(dirname "$0")"
status=0
for area in hal halcompile hdl synth pluto pluto-host vboard hm2 driver; do
    if [ -x "$area/run.sh" ]; then
        echo "=== bench/$area ==="
        if ! "./$area/run.sh"; then
            echo "bench/$area: FAILED"
            status=1
        fi
        echo
    fi
done
exit $status
