#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make demo` (for now): a small HAL session on the simulated clock.
# A 50 Hz sine from siggen is scaled (x10, +1), rectified by abs, added to
# the square wave by sum2 and converted to an integer, all in a 1 ms servo
# thread.  The threads run for exactly 5 ms and then 2 ms more of virtual
# time (halcmd's simrun), so the values printed are the same on every run.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${HM_BUILD:-$root/build}
export HAL_INSTANCE=demo-$$
hal=$(mktemp --suffix=.hal)
trap 'rm -f "$hal"' EXIT
cat > "$hal" <<'HAL'
loadrt threads name1=servo period1=1000000
loadrt siggen
loadrt scale
loadrt abs
loadrt sum2
loadrt conv_float_s32
addf siggen.0.update servo
addf scale.0 servo
addf abs.0 servo
addf sum2.0 servo
addf conv-float-s32.0 servo
setp siggen.0.frequency 50
setp scale.0.gain 10
setp scale.0.offset 1
net wave    siggen.0.sine   => scale.0.in
net scaled  scale.0.out     => abs.0.in
net rect    abs.0.out       => sum2.0.in0
net square  siggen.0.square => sum2.0.in1
net total   sum2.0.out      => conv-float-s32.0.in
net counts  conv-float-s32.0.out
loadusr -w echo --- after 5 ms of virtual time:
simrun 5ms
show sig
loadusr -w echo --- after 2 ms more:
simrun 2ms
show sig
show thread
HAL
echo "HAL demo on the simulated clock (halrun -S, HAL_INSTANCE=$HAL_INSTANCE)"
"$build/bin/halrun" -S -f "$hal"
