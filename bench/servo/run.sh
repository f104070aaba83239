#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# bench/servo: the hm2 servo path through hm2_sim (docs/hm2_sim.md
# "PERFORMANCE"): read + write of every TRAM register of a 5i20 SVST8_4
# with all modules, socket board vs in-process board (inproc=1), the
# in-process time split into Verilated model and transport, and scaling
# with 1, 2, 4 in-process boards at servo periods of 250 us, 500 us, 1 ms.
# Anchors: goal <= 5 us transport and <= 20 us in total (fast model);
# hm2_eth ~104 us, a SoC over UIO ~59 us on real hardware.
# Runs on its own: bench/servo/run.sh (uses $HM_BUILD or build/).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
export HM_BUILD="${HM_BUILD:-$root/build}"
for f in "$HM_BUILD/bin/vboard" "$HM_BUILD/bin/halrun" "$HM_BUILD/lib/rtlib/hm2_sim.so" \
    "$HM_BUILD/lib/libvboard_inproc.so"; do
    if [ ! -e "$f" ]; then
        echo "bench/servo: $f not built (source scripts/env.sh and make build)"
        exit 1
    fi
done
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cc -O2 -o "$tmp/tscfreq" "$root/bench/hm2/tscfreq.c"
py="$root/.venv/bin/python"
[ -x "$py" ] || py=python3
"$py" "$here/servo_bench.py" "$("$tmp/tscfreq")"
