#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# bench/vboard: speed of the virtual board (docs/vboard.md "PERFORMANCE").
#   1. simulated ClockLow cycles per wall second, 5i20 SVST8_4, idle and with
#      4 stepgens running; anchor: real time = 33.33 M ClockLow cycles/s.
#   2. wall time of one servo cycle's read+write (the hm2 driver's per-period
#      register lists, one READ + one WRITE request) with no time advance and
#      with a 1 ms advance per cycle; anchor: goal <= 20 us, hm2_eth ~100 us,
#      SoC bridge 59 us.
#   3. the bare protocol round trip (HELLO), for reference.
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
    "$vb" --socket "$dir/vb.sock" --board "${BOARD:-5i20}" --firmware "${FW:-SVST8_4}" "$@" \
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

echo "5i20 SVST8_4, $(nproc) CPUs; anchors: real time = 33.333 M ClockLow cycles/s;"
echo "read+write goal <= 20 us (hm2_eth ~100 us, SoC bridge 59 us)"
start_board
printf "simulation, idle:               "; "$bench" "$dir/vb.sock" speed 20
stop_board
start_board
printf "simulation, 4 stepgens running: "; "$bench" "$dir/vb.sock" speed 20 steps
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
printf "5i25 7I76x2 simulation, idle:   "; "$bench" "$dir/vb.sock" speed 20
stop_board
