#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# bench/vboard: speed of the virtual board (docs/vboard.md "PERFORMANCE").
#   1. simulated ClockLow cycles per wall second, 5i20 SVST8_4, idle and with
#      4 stepgens running; anchor: real time = 33.33 M ClockLow cycles/s.
#      Beside it the same per CPU second of the board process (its utime +
#      stime over the run): on a shared machine the wall figure also
#      measures the other load.  Idle once more with VBOARD_EVAL=full (each
#      evaluation through V::eval(), as before the scheduler was called
#      directly; sim/verilator/src/localbus_model.h).
#   2. wall time of one servo cycle's read+write (the hm2 driver's per-period
#      register lists, one READ + one WRITE request) with no time advance and
#      with a 1 ms advance per cycle; anchor: goal <= 20 us, hm2_eth ~100 us,
#      SoC bridge 59 us.
#   3. the bare protocol round trip (HELLO), for reference.
#   4. the 5i25 7I76x2 (ClockLow only) and the Pluto-P's pluto_servo (one
#      40 MHz clock; with and without VBOARD_EVAL=full) simulation speed.
#   5. the fast model (vboard --model fast) beside the RTL model (--model
#      rtl): 5i20 SVST8_4 idle and with every module at work (vboard-bench
#      speed MS active: 4 stepgens at 100/60/30/10 k steps/s, 8 PWMs at
#      20 kHz, 8 encoders fed by quadrature sources of 1-80 k counts/s);
#      then bench/vboard/fastdiff.sh (FASTDIFF=0 skips it: 10^6 operations
#      per module against the RTL model take tens of minutes).
# Runs on its own: bench/vboard/run.sh (uses $HM_BUILD or build/).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${HM_BUILD:-$root/build}"
vb="$build/bin/vboard"
bench="$build/bin/vboard-bench"
for f in "$vb" "$bench"; do
    if [ ! -x "$f" ]; then
        echo "bench/vboard: $f not built (needs Verilator: source scripts/env.sh and make build)"
        exit 1
    fi
done
dir="$(mktemp -d /tmp/vbbench.XXXXXX)"
pid=""
cleanup() {
    if [ -n "$pid" ]; then kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true; fi
    rm -rf "$dir"
}
trap cleanup EXIT

start_board() {
    # sections 1-4 measure the RTL model (the default would be the fast one)
    "$vb" --socket "$dir/vb.sock" --board "${BOARD:-5i20}" --firmware "${FW:-SVST8_4}" \
        --model rtl "$@" \
        >"$dir/out" 2>"$dir/err" &
    pid=$!
    for _ in $(seq 100); do
        grep -q "ready on" "$dir/out" 2>/dev/null && return 0
        sleep 0.05
    done
    echo "bench/vboard: vboard did not start: $(cat "$dir/err")"
    exit 1
}
stop_board() { kill "$pid"; wait "$pid" || true; pid=""; }
# cpu_ticks: utime + stime of the board process, in clock ticks.
cpu_ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }
# speed ARGS...: the bench's speed line, then the rate per board CPU second.
speed() {
    local t0 t1 line
    t0=$(cpu_ticks)
    line=$("$bench" "$dir/vb.sock" speed "$@")
    t1=$(cpu_ticks)
    python3 - "$line" "$t0" "$t1" "$(getconf CLK_TCK)" "${RT_HZ:-33.333e6}" <<'PY'
import re
import sys

line, t0, t1, hz = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
rt = float(sys.argv[5])  # the board's clock: real time in cycles per second
print(line)
m = re.search(r"\((\d+) cycles in", line)
cpu = (t1 - t0) / hz
if m and cpu > 0:
    rate = int(m.group(1)) / cpu
    print(f"{'':32}{rate / 1e6:.3f} M clock cycles per board CPU second "
          f"({cpu:.2f} s CPU, {100 * rate / rt:.1f}% of real time at {rt / 1e6:.3f} MHz)")
PY
}

echo "5i20 SVST8_4, $(nproc) CPUs; anchors: real time = 33.333 M ClockLow cycles/s;"
echo "read+write goal <= 20 us (hm2_eth ~100 us, SoC bridge 59 us)"
start_board
printf "simulation, idle:               "; speed 60
stop_board
VBOARD_EVAL=full start_board
printf "idle, VBOARD_EVAL=full:         "; speed 60
stop_board
start_board
printf "simulation, 4 stepgens running: "; speed 60 steps
printf "servo read+write, no advance:   "; "$bench" "$dir/vb.sock" servo 2000 0
printf "servo read+write, 1 ms advance: "; "$bench" "$dir/vb.sock" servo 30 1000000
printf "protocol alone (HELLO):         "; "$bench" "$dir/vb.sock" hello 5000
stop_board
# --spin: the board polls without sleeping for 200 us after each request.
start_board --spin 200
printf "servo read+write, --spin 200:   "; "$bench" "$dir/vb.sock" servo 2000 0
printf "protocol alone, --spin 200:     "; "$bench" "$dir/vb.sock" hello 5000
# ... and the client busy-polls for its replies too (vbclient spin_us).
printf "servo r+w, both sides spin:     "; VBBENCH_SPIN_US=200 "$bench" "$dir/vb.sock" servo 2000 0
printf "protocol alone, both spin:      "; VBBENCH_SPIN_US=200 "$bench" "$dir/vb.sock" hello 5000
stop_board
printf "machine floor (socketpair):     "; "$bench" pingpong 5000
# The 5i25's 7I76x2 has no ClockHigh logic (no PWM): only ClockLow edges run.
BOARD=5i25 FW=7I76x2 start_board
printf "5i25 7I76x2 simulation, idle:   "; speed 100
stop_board
# The Pluto-P runs one 40 MHz clock (vboard-bench's own line counts its
# cycles as ClockLow cycles of 33.33 MHz; the CPU line uses 40 MHz).
BOARD=pluto FW=pluto_servo start_board
printf "Pluto-P pluto_servo, idle:      "; RT_HZ=40e6 speed 100
stop_board
VBOARD_EVAL=full BOARD=pluto FW=pluto_servo start_board
printf "same, VBOARD_EVAL=full:         "; RT_HZ=40e6 speed 100
stop_board

# 5. The fast model beside the RTL model.
quads="--quad 3:2:80000 --quad 1:0:-60000 --quad 15:14:40000 --quad 13:12:20000"
quads="$quads --quad 27:26:10000 --quad 25:24:-5000 --quad 39:38:2000 --quad 37:36:1000"
echo "fast model vs RTL model, 5i20 SVST8_4 (goal: fast >= 10x real time, RTL >= 0.1x):"
start_board --model fast
printf "fast, idle:                     "; speed 10000
stop_board
# shellcheck disable=SC2086
start_board --model fast $quads
printf "fast, all modules active:       "; speed 2000 active
stop_board
# shellcheck disable=SC2086
start_board --model rtl $quads
printf "rtl, all modules active:        "; speed 30 active
stop_board
if [ "${FASTDIFF:-1}" != 0 ]; then
    "$root/bench/vboard/fastdiff.sh"
fi
