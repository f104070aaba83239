#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make bench`: every speed figure of the project, each printed next to its
# anchor (LinuxCNC 2.9 measured on this machine when installed, or the
# published figure).  Not part of `make test`.  Every folder bench/<area>/
# has its own run.sh, runnable on its own:
#   eth         servo-cycle round trip over loopback UDP (virtual 7i96S, LBP16)
#   components  per-call cost of lut5, mux16, pid, stepgen, encoder, pwmgen vs 2.9
#   hal         HAL per-function dispatch cost and HAL file load time, vs 2.9
#   halcompile  a generated component vs a hand-written one vs LinuxCNC, per call
#   halview     scope_rt's cost per sample in the thread; the live page's rate and latency
#   hdl         hm2 stepgen/encoder/pwmgen speed figures vs Mesa's anchors
#   hm2         hostmot2 + hm2_sim read/write time per servo cycle
#   machines    what the machine models (vboard --machine) add to a servo cycle
#   pluto       Pluto-P firmware: EPP traffic, PWM frequency, step rate
#   pluto-host  Pluto-P driver: EPP cycles and host time per servo cycle
#   servo       hm2 servo read+write: socket vs in-process board (hm2_sim inproc=1), scaling
#   synth       yosys LUT/FF per module, nextpnr-ice40 fmax of a slice
#   vboard      virtual board round trips
# This script runs them in turn and keeps going when one fails, so one broken
# bench does not hide the others; a folder without an executable run.sh is a
# failure too.  The exit status is 1 when any failed.
set -uo pipefail
cd "$(dirname "$0")"
status=0
for dir in */; do
    area=${dir%/}
    echo "=== bench/$area ==="
    if [ ! -x "$area/run.sh" ]; then
        echo "bench/$area: no executable run.sh: FAILED"
        status=1
    elif ! "./$area/run.sh"; then
        echo "bench/$area: FAILED"
        status=1
    fi
    echo
done
exit $status
