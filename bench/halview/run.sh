#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# bench/halview (not part of `make test`):
#  1. scope_rt's cost per sample, in rtapi_app where the thread runs it:
#     scope_cost.c, a realtime module loaded after scope_rt, calls
#     scope.sample 2,000,000 times per configuration and divides the CPU time
#     of its thread (CLOCK_THREAD_CPUTIME_ID: other load on the machine does
#     not count) - idle, 16 channels armed (13 pins of every type, 6 of them
#     linked, 2 signals, 1 more pin; a trigger compared every sample), 16
#     channels rolling, 1 channel armed.  Goal (issue 11): <= 50 ns for 16
#     channels.  (THREAD.time is too coarse for this: a virtual machine's
#     time-stamp counter may tick in steps of 26 clocks.)
#  2. the live page with 100 watched pins in headless chromium
#     (bench_halview.py): updates per second received and drawn at --rate 20
#     and --rate 100, and the latency from the server reading HAL to the
#     page's next animation frame (median, 99th percentile), wall clock.
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
cc -O2 -shared -fPIC -Wall -Wextra -Werror -std=c11 -I "$root/host/hal/include" \
    -I "$root/tools/halview/native" -o "$tmp/scope_cost.so" "$here/scope_cost.c" \
    -L "$build/lib" -Wl,-rpath,"$build/lib" -lhalview -lhal
printf 'loadrt scope_rt\nloadrt scope_cost\n' > "$tmp/cost.hal"
# scope_cost fails its load on purpose once it has printed (nothing stays loaded)
out=$( (HAL_RTLIB_PATH=$tmp HAL_INSTANCE=hvcost$$ halrun -k -f "$tmp/cost.hal" 2>&1 || true) |
    sed -n 's/^scope_cost: \([0-9. -]*\)$/\1/p')
[ -n "$out" ] || { echo "bench/halview: scope_cost printed nothing"; exit 1; }
read -r idle armed16 roll16 armed1 <<< "$out"
echo "scope_rt: scope.sample CPU time per call, 2,000,000 calls each (load average $(cut -d' ' -f1 /proc/loadavg)):"
echo "  16 channels armed (trigger compared): $armed16 ns   goal <= 50 ns"
echo "  16 channels roll:                     $roll16 ns"
echo "  1 channel armed:                      $armed1 ns"
echo "  idle (not armed):                     $idle ns"
HAL_INSTANCE=hvpage$$ python "$here/bench_halview.py"
