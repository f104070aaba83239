#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# EPP cycles, modelled EPP bus time and host time per servo cycle of the
# pluto_servo and pluto_step drivers: against the register model (driver
# cost alone, wide and byte I/O) and, when the virtual board is built,
# against a virtual Pluto (round trips included).  Runnable on its own.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${HM_BUILD:-$ROOT/build}"
BENCH="$BUILD/bin/pluto_bench"
if [ ! -x "$BENCH" ]; then
    echo "pluto-host: $BENCH not built (make build)" >&2
    exit 1
fi
echo "--- register model, epp_wide=1"
"$BENCH" --cycles 20000
echo "--- register model, epp_wide=0"
"$BENCH" --cycles 20000 --narrow
VB="$BUILD/bin/vboard"
FW="$BUILD/lib/firmware"
if ! [ -x "$VB" ] || ! [ -f "$FW/pluto_servo.rbf" ] || ! [ -f "$FW/pluto_step.rbf" ]; then
    echo "bench/pluto-host: the virtual board or the pluto firmware is not built ($VB, $FW): run make build" >&2
    exit 1
fi
exec python3 "$ROOT/bench/pluto-host/vboard_bench.py" "$BUILD"
