#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# bench/hm2: the hostmot2 driver against the virtual 5i20 (SVST8_4) through
# hm2_sim, measured in HAL (docs/hm2_sim.md "PERFORMANCE").
#   1. wall clock, 1 ms servo thread: hm2_5i20.0.read.time + write.time (the
#      driver's whole per-cycle I/O: one READ and one WRITE round trip),
#      median of the sampled periods, with hm2_sim host_time=0 (transport
#      only: the board's clocks stand still), also with hm2_sim spin_us=200
#      and vboard --spin 200 (both sides busy-poll), with async_writes=1 (the
#      write's reply is read with the next request), and against a
#      free-running board (each request waits for the simulation).
#      Anchors: goal <= 20 us; hm2_eth ~100 us waiting for reads; SoC 59 us.
#   2. simulated clock (halrun -S, lockstep): wall time per 1 ms servo cycle
#      including the board simulating that millisecond, and the simulated
#      ClockLow cycles per wall second.  Anchor: real time = 33.333 M/s.
# Runs on its own: bench/hm2/run.sh (uses $HM_BUILD or build/).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${HM_BUILD:-$root/build}"
export HM_BUILD=$build
for f in "$build/bin/vboard" "$build/bin/halrun" "$build/lib/rtlib/hm2_sim.so"; do
    if [ ! -e "$f" ]; then
        echo "bench/hm2: $f not built (source scripts/env.sh and make build)"
        exit 1
    fi
done
dir="$(mktemp -d /tmp/hm2bench.XXXXXX)"
pid=""
cleanup() {
    if [ -n "$pid" ]; then kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; fi
    rm -rf "$dir"
}
trap cleanup EXIT

cc -O2 -o "$dir/tscfreq" "$(dirname "$0")/tscfreq.c"
hz=$("$dir/tscfreq")

start_board() {
    "$build/bin/vboard" --socket "$dir/vb.sock" --board 5i20 --firmware SVST8_4 "$@" \
        >"$dir/out" 2>"$dir/err" &
    pid=$!
    for _ in $(seq 100); do
        grep -q "ready on" "$dir/out" 2>/dev/null && return 0
        sleep 0.05
    done
    echo "bench/hm2: vboard did not start: $(cat "$dir/err")"
    exit 1
}
stop_board() { kill "$pid"; wait "$pid" || true; pid=""; }

load_hal() { # extra hm2_sim args
    cat <<HAL
loadrt hostmot2
loadrt hm2_sim socket=$dir/vb.sock board=5i20 $1 config="num_encoders=1 num_pwmgens=1 num_stepgens=3"
loadrt threads name1=servo period1=1000000
addf hm2_5i20.0.read servo
addf hm2_5i20.0.write servo
setp hm2_5i20.0.stepgen.00.enable 1
setp hm2_5i20.0.stepgen.00.control-type 1
setp hm2_5i20.0.stepgen.00.steplen 5000
setp hm2_5i20.0.stepgen.00.stepspace 5000
setp hm2_5i20.0.stepgen.00.position-scale 1000
setp hm2_5i20.0.stepgen.00.maxaccel 0
setp hm2_5i20.0.stepgen.00.velocity-cmd 10
HAL
}

# wall clock: sample read.time / write.time every ~20 ms for ~2 s
wall_run() { # label, hm2_sim args
    {
        load_hal "$2"
        echo "start"
        echo "loadusr -w sleep 0.5"
        for _ in $(seq 80); do
            echo "loadusr -w sleep 0.02"
            echo "getp hm2_5i20.0.read.time"
            echo "getp hm2_5i20.0.write.time"
        done
        echo "getp hm2_5i20.0.io_error"
        echo "stop"
    } > "$dir/wall.hal"
    HAL_TIMING_EVERY=1 HAL_INSTANCE=hm2bench$$ "$build/bin/halrun" -f "$dir/wall.hal" > "$dir/wall.out" 2>&1 || {
        cat "$dir/wall.out"; echo "bench/hm2: halrun failed"; exit 1; }
    grep -q '^TRUE$' "$dir/wall.out" && { echo "bench/hm2: io_error during the run"; exit 1; }
    python3 - "$dir/wall.out" "$hz" "$1" <<'PY'
import statistics, sys
vals = [int(l) for l in open(sys.argv[1]) if l.strip().lstrip("-").isdigit()]
hz = float(sys.argv[2])
pairs = [(vals[i], vals[i + 1]) for i in range(0, len(vals) - 1, 2) if vals[i] > 0 and vals[i + 1] > 0]
us = sorted((r + w) / hz * 1e6 for r, w in pairs)
rd = statistics.median(r for r, _ in pairs) / hz * 1e6
wr = statistics.median(w for _, w in pairs) / hz * 1e6
print(f"{sys.argv[3]:<36} read+write median {statistics.median(us):6.1f} us "
      f"(read {rd:.1f}, write {wr:.1f}; p90 {us[int(len(us) * 0.9)]:.1f}; {len(us)} samples)"
      f"   goal <= 20 us, hm2_eth ~100 us, SoC 59 us")
PY
}

echo "virtual 5i20 SVST8_4 through hostmot2 + hm2_sim; $(nproc) CPUs, TSC $(awk -v h="$hz" 'BEGIN{printf "%.3f", h/1e9}') GHz"
# The board simulates at a few % of real time, so on the wall clock it
# cannot follow HAL: the transport figures run with host_time=0 (requests
# never advance the board; its registers answer, its clocks stand still),
# the simulation's own cost is the simulated-clock figure below.
start_board
wall_run "wall clock, 1 ms thread:" "host_time=0"
stop_board
start_board
wall_run "wall clock, async_writes=1:" "host_time=0 async_writes=1"
stop_board
start_board --spin 200
wall_run "wall clock, both sides spin 200 us:" "host_time=0 spin_us=200"
wall_run "spin 200 us + async_writes=1:" "host_time=0 spin_us=200 async_writes=1"
stop_board
start_board --freerun
wall_run "wall clock, board free-running:" ""
stop_board

# simulated clock, lockstep: 100 servo periods of 1 ms
printf '#!/bin/sh\ndate +%%s.%%N > "$1"\n' > "$dir/stamp"
chmod +x "$dir/stamp"
start_board
{
    load_hal ""
    echo "simrun 5ms"
    echo "loadusr -w $dir/stamp $dir/t0"
    echo "simrun 100ms"
    echo "loadusr -w $dir/stamp $dir/t1"
    echo "getp hm2_5i20.0.stepgen.00.counts"
} > "$dir/sim.hal"
HAL_INSTANCE=hm2sim$$ "$build/bin/halrun" -S -f "$dir/sim.hal" > "$dir/sim.out" 2>&1 || {
    cat "$dir/sim.out"; echo "bench/hm2: halrun -S failed"; exit 1; }
stop_board
awk -v a="$(cat "$dir/t0")" -v b="$(cat "$dir/t1")" 'BEGIN {
    w = b - a; clk = 33333333 * 0.100
    printf "%-36s %6.1f ms wall per 1 ms servo cycle; %.2f M ClockLow/s = %.1f%% of real time   anchor: real time 33.333 M/s\n",
        "simulated clock (lockstep):", w / 100 * 1000, clk / w / 1e6, clk / w / 33333333 * 100 }'
