#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Component benchmark (not part of `make test`): the per-call cost of
# halcompile-built logic components against LinuxCNC 2.9 running the same
# HAL file.
#
# For each component, N instances' functions run in one thread with a
# 100 us period; the thread's own run time (THREAD.time, time-stamp-counter
# clocks, measured the same way by LinuxCNC and by us) is read many times
# while it runs, and the median is divided by N.  Columns:
#   ours      lib/rtlib/NAME.so with HAL_TIMING_EVERY=0 (functions not timed)
#   ours+t    the same with HAL_TIMING_EVERY=1: every function timed every
#             period, as LinuxCNC always does (bench/hal shows that cost)
#   LinuxCNC  LinuxCNC 2.9's NAME through lcnc-halrun, when installed
#             (COMPONENTS_BENCH_LCNC=0 leaves it out)
# Goal: ours <= 0.5 x LinuxCNC.  The inputs change every period (a streamer
# is not needed: siggen's clock drives in-0 of every lut5 through a net).
#
# Then the servo components (bench.py): pid.N.do-pid-calcs,
# stepgen.make-pulses, encoder.update-counters and pwmgen.make-pulses, each
# HAL file with three threads of about 100 us (100, 101 and 103, so they
# seldom wake during each other's run): `f` with the measured functions (16
# pid loops; one make-pulses or update-counters serving 16 or 8 channels),
# `base` with as many calls of and2, and `drive` with what feeds them
# (siggen; stepgens whose quadrature the encoder counts; update-freq,
# pwmgen.update) and a sampler recording the two threads' run times every
# period.  Per call = (mean of the middle half of f - the same of base) /
# calls: the function's own cost, HAL's dispatch and per-function timing
# cancelling (bench/hal compares those).  The session runs on one CPU (the
# last; COMP_BENCH_CPU=N or `any`), as LinuxCNC's realtime threads do; the
# figure is the median of COMP_BENCH_REPS (5) runs alternating ours and
# LinuxCNC, each of HAL_BENCH_SAMPLES_SERVO (3000) periods, with the range.
#
#   bench/components/run.sh [pid stepgen encoder pwmgen]   (default: all four)
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${HM_BUILD:-$root/build}
n_all=${COMPONENTS_BENCH_N:-500}
n=$n_all
samples=${HAL_BENCH_SAMPLES:-200}
period=100000
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# gen COMP LOADARGS SETUP -> HAL file: one thread, n instances of COMP fed
# by a changing bit, THREAD.time read `samples` times.
gen() {
    local comp=$1 args=$2 setup=$3 prefix=$4 inpin=$5
    echo "loadrt threads name1=tb period1=$period"
    echo "loadrt siggen"
    echo "addf siggen.0.update tb"
    echo "setp siggen.0.frequency 1000"
    echo "loadrt $comp $args"
    for ((i = 0; i < n; i++)); do
        echo "addf $prefix.$i tb"
        [ -n "$inpin" ] && echo "net clk $prefix.$i.$inpin"
        [ -n "$setup" ] && echo "setp $prefix.$i.${setup/:/ }"
    done
    echo "net clk siggen.0.clock"
    echo "start"
    echo "loadusr -w sleep 0.5"
    for ((i = 0; i < samples; i++)); do
        echo "getp tb.time"
        echo "loadusr -w sleep 0.01"
    done
    echo "stop"
}
median() {
    python3 -c "
import statistics, sys
v = [int(x) for x in sys.stdin.read().split() if x.lstrip('-').isdigit()]
print(statistics.median(v) / $n if v else 'nan')"
}
ours() { # timing_every
    HAL_TIMING_EVERY=$1 HAL_INSTANCE=cbench$$ "$build/bin/halrun" -f "$tmp/b.hal" 2>/dev/null |
        median
}
lcnc() {
    if [ "${COMPONENTS_BENCH_LCNC:-1}" = 0 ] || ! command -v lcnc-halrun >/dev/null; then
        echo nan
        return
    fi
    # LinuxCNC's halrun refuses to start while any process called rtapi_app
    # runs (ours included); as root, give it a pid namespace of its own.
    if [ "$(id -u)" = 0 ] && command -v unshare >/dev/null; then
        unshare --pid --fork --mount-proc bash -c 'lcnc-halrun -f "$1"; wait' lcnc "$tmp/b.hal" \
            2>/dev/null | median
    else
        lcnc-halrun -f "$tmp/b.hal" 2>/dev/null | median
    fi
}

echo "components: clocks per function call, up to $n_all instances in a ${period} ns thread," \
     "median of $samples periods"
# name, load args, setp PIN:VALUE, instance prefix, input pin, most instances
while read -r comp args setup prefix inpin most; do
    [ "$args" = - ] && args=""
    [ "$setup" = - ] && setup=""
    # LinuxCNC's HAL memory holds 500 lut5 but not 500 mux16
    n=$(( most < n_all ? most : n_all ))
    gen "$comp" "$args count=$n" "$setup" "$prefix" "$inpin" > "$tmp/b.hal"
    o=$(ours 0)
    t=$(ours 1)
    l=$(lcnc)
    python3 - "$comp" "$o" "$t" "$l" "$n" <<'PY'
import sys
name, o, t, l = sys.argv[1], *(float(x) for x in sys.argv[2:5])
n = int(sys.argv[5])
print(f"  {name:6s} x{n:4d} ours {o:6.2f}   ours+t {t:6.2f}   LinuxCNC 2.9 {l:6.2f}"
      f"   (ours/LinuxCNC {o / l:.2f}, ours+t/LinuxCNC {t / l:.2f}, goal <= 0.5)")
PY
done <<'LIST'
lut5 - function:0x96696996 lut5 in-0 500
mux16 - use-graycode:TRUE mux16 sel0 200
LIST

HAL_BENCH_SAMPLES=${HAL_BENCH_SAMPLES_SERVO:-3000} \
    python3 "$here/bench.py" "$build/bin/halrun" "$build/lib/rtlib" "$@"
