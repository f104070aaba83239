#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# HAL benchmarks (not part of `make test`), each printed as
# "ours vs LinuxCNC" when LinuxCNC 2.9's halrun is installed:
#  1. per-function dispatch cost in a thread of 1,000 trivial functions
#     (and2): CPU time of rtapi_app with 1,000 functions minus with none,
#     per call, thread period 100 us, measured over a few seconds;
#  2. time to run a 2,000-line HAL file with halrun (load, link, setp,
#     addf, exit).
# Targets: dispatch <= 1/2 of LinuxCNC's, loading >= 3x faster.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${HM_BUILD:-$root/build}
ours=$build/bin/halrun
secs=${HAL_BENCH_SECONDS:-3}
period=100000
nf=1000
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
have_lcnc=0
[ -x /usr/bin/halrun ] && [ -x /usr/bin/rtapi_app ] && have_lcnc=1
export RTAPI_UID=65534 RTAPI_FIFO_PATH=/tmp/.rtapi_fifo

lcnc_reset() {
    for _ in 1 2 3 4 5; do
        /usr/bin/halrun -U >/dev/null 2>&1
        /usr/lib/linuxcnc/realtime status >/dev/null 2>&1 || return 0
        sleep 0.5
    done
}

# cpu_per_call HALRUN RTAPI_EXE INSTANCE -> prints ns per function call
cpu_cost() {
    local halrun=$1 exe=$2 inst=$3 n=$4
    local out=$tmp/cpu.$n.$inst
    rm -f "$out"
    python3 "$here/gen.py" dispatch "$n" "$period" "$secs" "$exe" "$out" "$inst" > "$tmp/d.hal"
    if [ "$halrun" = /usr/bin/halrun ]; then lcnc_reset; fi
    HAL_INSTANCE=$inst "$halrun" -f "$tmp/d.hal" >/dev/null 2>&1
    [ -s "$out" ] || { echo "nan"; return; }
    python3 -c "import sys; a=[float(x) for x in open('$out')]; print(a[1]-a[0])"
}

per_call() { # halrun exe inst
    local c0 c1
    c0=$(cpu_cost "$1" "$2" "$3" 0)
    c1=$(cpu_cost "$1" "$2" "$3" $nf)
    python3 -c "
c0, c1 = float('$c0'), float('$c1')
calls = $nf * $secs * 1e9 / $period
print(f'{(c1 - c0) / calls * 1e9:.2f}')"
}

echo "HAL dispatch: $nf trivial functions (and2) in a ${period} ns thread, ${secs} s"
o=$(per_call "$ours" "$build/bin/rtapi_app" "bench$$")
o1=$(HAL_TIMING_EVERY=1 per_call "$ours" "$build/bin/rtapi_app" "bench1$$")
if [ $have_lcnc = 1 ]; then
    l=$(per_call /usr/bin/halrun /usr/bin/rtapi_app "")
    python3 -c "print(f'dispatch ns/function: ours {float(\"$o\"):.2f} vs LinuxCNC {float(\"$l\"):.2f}  (ratio {float(\"$o\")/float(\"$l\"):.2f}, target <= 0.5)')"
    python3 -c "print(f'  with every function timed every period (HAL_TIMING_EVERY=1, as LinuxCNC): ours {float(\"$o1\"):.2f} (ratio {float(\"$o1\")/float(\"$l\"):.2f})')"
else
    echo "dispatch ns/function: ours $o, timing every period $o1 (LinuxCNC not installed)"
fi

python3 "$here/gen.py" load > "$tmp/load.hal"
lines=$(wc -l < "$tmp/load.hal")
time_run() { # halrun inst -> seconds (best of 3)
    local best=999
    for _ in 1 2 3; do
        if [ "$1" = /usr/bin/halrun ]; then lcnc_reset; fi
        local t0 t1
        t0=$(date +%s.%N)
        HAL_INSTANCE=$2 "$1" -f "$tmp/load.hal" >/dev/null 2>&1
        t1=$(date +%s.%N)
        best=$(python3 -c "print(min($best, $t1 - $t0))")
    done
    echo "$best"
}
echo "HAL file load: $lines lines (3 components x 200, nets, setp, addf), best of 3"
o=$(time_run "$ours" "bench$$")
if [ $have_lcnc = 1 ]; then
    l=$(time_run /usr/bin/halrun "")
    python3 -c "print(f'load seconds: ours {$o:.3f} vs LinuxCNC {$l:.3f}  (LinuxCNC/ours {$l/$o:.1f}x faster, target >= 3x)')"
else
    echo "load seconds: ours $o (LinuxCNC not installed)"
fi
