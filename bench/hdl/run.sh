#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# HDL speed figures of the hm2 stepgen, encoder and pwmgen, measured in
# simulation (Verilator) and printed next to Mesa's anchors at the same
# clocks.  Standalone: bash bench/hdl/run.sh (needs the venv: make deps).
# Exit status 1 when a figure is below its anchor or a measurement failed.
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
# shellcheck source=/dev/null
source "$ROOT/scripts/env.sh"
log="$(mktemp /tmp/hm2-bench-hdl.XXXXXX.log)"
python "$ROOT/bench/hdl/run_bench.py" 2>"$log"
rc=$?
if [ $rc -ne 0 ]; then
    echo "bench/hdl: failed (rc=$rc), last lines of $log:"
    tail -n 30 "$log"
else
    rm -f "$log"
fi
exit $rc
