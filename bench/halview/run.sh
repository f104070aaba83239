#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# bench/halview (not part of `make test`):
#  1. scope_rt's cost per sample in the thread, 16 channels (pins and
#     signals of every type): a wall-clock HAL session with a 100 us thread
#     running only scope.sample; the thread's own run time (THREAD.time, TSC
#     clocks, every period) sampled while the scope is armed and waiting for
#     a trigger that never comes (every period stores 16 values and compares
#     the trigger) and while it rolls (stores, publishes), minus the same
#     thread with scope.sample idle; the TSC frequency from bench/hm2/tscfreq.c.
#     Goal (issue 11): <= 50 ns for 16 channels.
#  2. the live page with 100 watched pins, in headless chromium: updates per
#     second received and drawn at --rate 20 and --rate 100, and the latency
#     from the server reading HAL to the page's next animation frame
#     (median, 99th percentile).
# Runs on its own: bench/halview/run.sh (uses $HM_BUILD or build/).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${HM_BUILD:-$root/build}
export HM_BUILD=$build PATH="$build/bin:$root/.venv/bin:$PATH"
for f in "$build/bin/halscope" "$build/lib/rtlib/scope_rt.so" "$build/lib/libhalview.so"; do
    [ -e "$f" ] || { echo "bench/halview: $f not built (make build)"; exit 1; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cc -O2 -o "$tmp/tscfreq" "$root/bench/hm2/tscfreq.c"
hz=$("$tmp/tscfreq")
python "$here/bench_halview.py" --tsc-hz "$hz" --tmp "$tmp"
