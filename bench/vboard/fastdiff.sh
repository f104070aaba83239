#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# bench/vboard/fastdiff.sh: the fast board model against the Verilated
# firmware, 10^6 operations per module (make test runs 1000:
# tests/vboard/test_fast_models.py).  Operations are bus writes and burst
# reads, time advances (up to 100 us; --long caps the rare longer ones at
# 200 us here so the RTL side stays within minutes), pin drives and
# quadrature sources; every read and pin edge is compared.  Prints each
# module's line and the wall time.  OPS=N overrides the count.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${HM_BUILD:-$root/build}"
diff="$build/bin/vboard-fastdiff"
if [ ! -x "$diff" ]; then
    echo "bench/vboard/fastdiff.sh: $diff not built (make build)"
    exit 1
fi
ops="${OPS:-1000000}"
run() {
    local t0 t1
    t0=$(date +%s.%N)
    "$diff" --board "$1" --firmware "$2" --module "$3" --ops "$ops" --long 200000 --seed 11
    t1=$(date +%s.%N)
    echo "    ($(python3 -c "print(f'{$t1 - $t0:.1f}')") s wall)"
}
for m in idrom watchdog ioport led encoder stepgen pwmgen all; do
    run 5i20 SVST8_4 "$m"
done
for m in ioport encoder stepgen all; do
    run 5i25 7I76x2 "$m"
done
