#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# halcompile benchmark (not part of `make test`): the per-call cost of a
# halcompile-built component against the same component written by hand in
# C, and against LinuxCNC 2.9 running the same HAL file.
#
# For each component (and2: bit logic, no floating point; ddt: floating
# point with per-instance state) one thread per variant runs N instances'
# functions with a 100 us period, all variants in the same session; each
# thread's own run time (THREAD.time, time-stamp-counter clocks, measured
# identically by LinuxCNC and us) is read in turn many times while they run
# and each median is divided by N.  Variants:
#   comp   lib/rtlib/NAME.so, built from host/hal/components/NAME.comp
#   hand   bench/halcompile/NAME_hand.c, compiled here with `halcompile
#          --compile` (same -O2 as the tree)
#   lcnc   LinuxCNC 2.9's NAME (via lcnc-halrun), when installed
#          (HALCOMPILE_BENCH_LCNC=0 leaves it out)
# Our figures use HAL_TIMING_EVERY=0 (no per-function timing) for both of
# ours; LinuxCNC times every function every period, so the LinuxCNC column
# includes that cost (bench/hal shows it separately).
# Goal: comp <= hand (within noise).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${HM_BUILD:-$root/build}
n=${HALCOMPILE_BENCH_N:-500}
samples=${HAL_BENCH_SAMPLES:-200}
period=100000
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for c in and2_hand ddt_hand; do
    (cd "$tmp" && "$build/bin/halcompile" --compile "$here/$c.c") || exit 1
done

# gen "PREFIX MODULE THREAD"... -> HAL file: one thread per variant, all
# with the same period, their THREAD.time read in turn `samples` times, so
# every variant sees the same machine load.
gen() {
    local v prefix mod th threads=""
    for v in "$@"; do
        read -r prefix mod th <<< "$v"
        threads+=" $th"
    done
    local names="" periods="" k=1
    for th in $threads; do names+=" name$k=$th"; periods+=" period$k=$period"; k=$((k + 1)); done
    echo "loadrt threads$names$periods"
    for v in "$@"; do
        read -r prefix mod th <<< "$v"
        echo "loadrt $mod count=$n"
        for ((i = 0; i < n; i++)); do echo "addf $prefix.$i $th"; done
    done
    echo "start"
    echo "loadusr -w sleep 0.5"
    for ((i = 0; i < samples; i++)); do
        for th in $threads; do echo "getp $th.time"; done
        echo "loadusr -w sleep 0.01"
    done
    echo "stop"
}
# medians: the values of each thread are interleaved in the output
medians() { # nthreads
    python3 -c "
import statistics, sys
k = $1
v = [int(x) for x in sys.stdin.read().split() if x.lstrip('-').isdigit()]
print(' '.join(str(statistics.median(v[i::k]) / $n) if v[i::k] else 'nan' for i in range(k)))"
}
ours() { # comp -> "comp hand"
    gen "$1 $1 tc" "${1}-hand ${1}_hand th" > "$tmp/b.hal"
    HAL_TIMING_EVERY=0 HAL_INSTANCE=hcbench$$ HAL_RTLIB_DIR="$tmp:$build/lib/rtlib" \
        "$build/bin/halrun" -f "$tmp/b.hal" 2>/dev/null | medians 2
}
lcnc() { # comp
    if [ "${HALCOMPILE_BENCH_LCNC:-1}" = 0 ] || ! command -v lcnc-halrun >/dev/null; then
        echo nan
        return
    fi
    gen "$1 $1 tc" > "$tmp/l.hal"
    lcnc-halrun -f "$tmp/l.hal" 2>/dev/null | medians 1
}

echo "halcompile: clocks per function call, $n instances in a ${period} ns thread," \
     "median of $samples periods"
# insns SO SYMBOL -> number of instructions of that function (objdump)
insns() {
    objdump -d --no-show-raw-insn "$1" |
        awk -v s="<$2>:" '$2 == s {on = 1; next} on && NF == 0 {exit} on && /:\t/ {n++} END {print n + 0}'
}

for comp in and2 ddt; do
    echo "  $comp function code: comp $(insns "$build/lib/rtlib/$comp.so" __comp_fn__)" \
         "instructions, hand $(insns "$tmp/${comp}_hand.so" "${comp}_hand") instructions"
    read -r c h <<< "$(ours "$comp")"
    l=$(lcnc "$comp")
    python3 - "$comp" "$c" "$h" "$l" <<'PY'
import sys
name, c, h, l = sys.argv[1], *(float(x) for x in sys.argv[2:5])
print(f"  {name:5s} comp {c:6.2f}   hand {h:6.2f}   (comp/hand {c / h:.2f}, goal <= 1)"
      f"   LinuxCNC 2.9 {l:6.2f} (comp/LinuxCNC {c / l:.2f})")
PY
done
