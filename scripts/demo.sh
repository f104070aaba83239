#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make demo`: a virtual Mesa 5i20 running the SVST8_4 firmware (Verilated
# HostMot2, bin/vboard) driven by the real hostmot2 driver through hm2_sim,
# on HAL's simulated clock (halrun -S): examples/demo-5i20.hal.
#   1. start the board blank, with StepGen #0 Step/Dir looped into
#      Encoder #0 A/B (IO 48 -> 3, IO 49 -> 2 inverted);
#   2. load hostmot2 + hm2_sim: the driver loads firmware=hm2/5i20/SVST8_4.BIT
#      onto the blank board and prints the pinout report;
#   3. move stepgen 0 through one period of a 5 Hz sine (position mode), then
#      move to 0.25 and hold for 60 ms, printing commanded vs fed-back position (stepgen position-fb and
#      the encoder's count of the steps that came out of the pins).
# Every part is required: a missing one is an error, not a smaller demo.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${HM_BUILD:-$root/build}
export HM_BUILD=$build
export HAL_INSTANCE=demo-$$
tmp=$(mktemp -d)
vbpid=
cleanup() {
    if [ -n "$vbpid" ]; then kill "$vbpid" 2>/dev/null || true; wait "$vbpid" 2>/dev/null || true; fi
    rm -rf "$tmp"
}
trap cleanup EXIT

for part in bin/vboard bin/halrun lib/rtlib/hostmot2.so lib/rtlib/hm2_sim.so \
    lib/firmware/hm2/5i20/SVST8_4.BIT; do
    if [ ! -e "$build/$part" ]; then
        echo "demo: $build/$part is missing: run \`make build\` (make demo does)" >&2
        exit 1
    fi
done

sock=$tmp/5i20.sock
echo "=== starting a blank virtual 5i20: vboard --board 5i20 --loop 48:3 --loop 49:2:inv"
"$build/bin/vboard" --socket "$sock" --board 5i20 --loop 48:3 --loop 49:2:inv > "$tmp/vboard.log" 2>&1 &
vbpid=$!
for _ in $(seq 100); do
    grep -q ready "$tmp/vboard.log" && break
    kill -0 "$vbpid" 2>/dev/null || { cat "$tmp/vboard.log"; echo "demo: vboard failed" >&2; exit 1; }
    sleep 0.05
done
grep -q ready "$tmp/vboard.log" || { echo "demo: vboard did not come up" >&2; exit 1; }
cat "$tmp/vboard.log"

# The run: the example HAL file, then the trajectory in 20 ms slices of
# simulated time with the three positions read after each slice.
{
    echo "source $root/examples/demo-5i20.hal"
    for t in $(seq 20 20 200); do
        echo "simrun 20ms"
        echo "loadusr -w echo @@ $t"
        echo "gets cmd"; echo "gets fb"; echo "gets enc"
    done
    # then a last move to 0.25 (250 steps) and hold there
    echo "unlinkp hm2_5i20.0.stepgen.00.position-cmd"
    echo "setp hm2_5i20.0.stepgen.00.position-cmd 0.25"
    echo "simrun 60ms"
    echo "loadusr -w echo @@ 260"
    echo "getp hm2_5i20.0.stepgen.00.position-cmd"; echo "gets fb"; echo "gets enc"
    echo "getp hm2_5i20.0.stepgen.00.counts"
    echo "getp hm2_5i20.0.encoder.00.count"
} > "$tmp/run.hal"

echo "=== halrun -S: examples/demo-5i20.hal (DEMO_SOCKET=$sock)"
start=$(date +%s.%N)
DEMO_SOCKET=$sock "$build/bin/halrun" -S -f "$tmp/run.hal" > "$tmp/out.log" 2>&1 || {
    cat "$tmp/out.log"; echo "demo: halrun failed" >&2; exit 1; }
end=$(date +%s.%N)

echo "=== pinout report (as the driver logged it at load)"
grep -E '^hm2/hm2_5i20\.0:' "$tmp/out.log" | grep -v -E 'registered$' || true
echo
echo "=== stepgen 0 (position mode) through a 5 Hz sine, Step/Dir looped into encoder 0"
awk '
    /^@@ / { t = $2; n = 0; next }
    t != "" && n < 3 && $1 ~ /^-?[0-9.e+-]+$/ { v[n++] = $1;
        if (n == 3) { printf "  t=%4d ms  commanded %9.4f  stepgen fb %9.4f  encoder %9.4f\n", t, v[0], v[1], v[2]; last_t = t; c = v[0]; f = v[1]; e = v[2]; t = "" }
        next }
    t == "" && last_t == 260 && $1 ~ /^-?[0-9]+$/ { cnt[m++] = $1 }
    END {
        printf "\nat the end (t=%d ms, holding at %.4f):\n", last_t, c
        printf "  commanded position      %9.4f\n", c
        printf "  stepgen position-fb     %9.4f   (error %+.4f)\n", f, f - c
        printf "  encoder position        %9.4f   (error %+.4f)\n", e, e - c
        if (m == 2) printf "  steps generated %d, steps counted by the encoder %d\n", cnt[0], cnt[1]
    }' "$tmp/out.log"
awk -v s="$start" -v e="$end" 'BEGIN { printf "\n(simulated 260 ms of board and servo time in %.1f s wall)\n", e - s }'
