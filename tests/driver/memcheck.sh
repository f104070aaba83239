#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# valgrind memcheck of the driver side (for `make memcheck`): every C unit
# test of host/driver (hostmot2, sanitizing, probe, maths, .BIT, EPP ports,
# 7i43, PCI, hm2_sim llio, Pluto-P), then one halrun session on the
# simulated clock with hostmot2 + hm2_sim driving a virtual 5i20 for 20
# servo periods, rtapi_app itself under valgrind (HAL_RTAPI_APP).  Any
# memcheck error or definitely/indirectly lost block fails the run.
#
# Uses a build without sanitizers: $HM_BUILD, else build/ in this tree.
#   tests/driver/memcheck.sh            # everything
#   tests/driver/memcheck.sh unit       # the unit tests only
#   tests/driver/memcheck.sh session    # the HAL session only
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="${HM_BUILD:-$ROOT/build}"
WHAT="${1:-all}"
VG=(valgrind --tool=memcheck --error-exitcode=99 --leak-check=full
    --errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect
    --track-origins=yes --num-callers=30)
command -v valgrind >/dev/null || { echo "memcheck: valgrind is required (apt-get install valgrind)" >&2; exit 2; }
if [ -e "$BUILD/CMakeCache.txt" ] && grep -q '^SANITIZE:BOOL=ON' "$BUILD/CMakeCache.txt"; then
    echo "memcheck: $BUILD is a sanitizer build; valgrind needs a plain one (make build)" >&2
    exit 2
fi
TMP="$(mktemp -d /tmp/hm2memcheck.XXXXXX)"
trap 'rm -rf "$TMP"' EXIT
fail=0

unit() {
    local tests=(test_driver_hal test_driver_sanitize test_driver_probe test_driver_math
                 test_driver_config_bitfile test_epp_port test_hm2_7i43 test_hm2_7i43_core
                 test_hm2_pci test_hm2_sim test_pluto)
    for t in "${tests[@]}"; do
        local exe="$BUILD/bin/$t"
        [ -x "$exe" ] || { echo "memcheck: $exe missing (make build)" >&2; fail=1; continue; }
        if (cd "$TMP" && "${VG[@]}" --log-file="$TMP/$t.vg" "$exe" >"$TMP/$t.out" 2>&1); then
            echo "memcheck: $t: clean ($(grep -o 'ERROR SUMMARY: [0-9]* errors' "$TMP/$t.vg"))"
        else
            echo "memcheck: $t: FAILED" >&2
            tail -n 60 "$TMP/$t.vg" >&2
            tail -n 20 "$TMP/$t.out" >&2
            fail=1
        fi
    done
}

session() {
    local vb="$BUILD/bin/vboard" sock="$TMP/b.sock"
    [ -x "$vb" ] && [ -x "$BUILD/bin/halrun" ] || { echo "memcheck: vboard/halrun missing (make build)" >&2; fail=1; return; }
    "$vb" --socket "$sock" --board 5i20 --firmware SVST8_4 >"$TMP/vboard.out" 2>&1 &
    local vbpid=$!
    for _ in $(seq 100); do [ -S "$sock" ] && break; sleep 0.1; done
    cat >"$TMP/rtapi_app" <<WRAP
#!/bin/sh
exec ${VG[*]} --log-file=$TMP/rtapi_app.vg "$BUILD/bin/rtapi_app" "\$@"
WRAP
    chmod +x "$TMP/rtapi_app"
    cat >"$TMP/session.hal" <<HAL
loadrt hostmot2
loadrt hm2_sim socket=$sock config="num_encoders=2 num_pwmgens=2 num_stepgens=2"
loadrt threads name1=servo period1=1000000
addf hm2_5i20.0.read servo
addf hm2_5i20.0.write servo
setp hm2_5i20.0.stepgen.00.enable 1
setp hm2_5i20.0.stepgen.00.position-cmd 0.5
setp hm2_5i20.0.pwmgen.00.enable 1
setp hm2_5i20.0.pwmgen.00.value 0.3
setp hm2_5i20.0.gpio.012.is_output 1
simrun 20ms
show pin hm2_5i20.0.encoder.00
HAL
    local rc=0
    (cd "$TMP" && HAL_INSTANCE="memcheck-$$" HAL_RTAPI_APP="$TMP/rtapi_app" HAL_RTAPI_STDIO=inherit \
        HM_BUILD="$BUILD" "$BUILD/bin/halrun" -S -f "$TMP/session.hal" >"$TMP/session.out" 2>&1) || rc=$?
    kill "$vbpid" 2>/dev/null || true
    wait "$vbpid" 2>/dev/null || true
    # rtapi_app ends after halrun; its log is complete once valgrind wrote the summary
    for _ in $(seq 100); do grep -q 'ERROR SUMMARY' "$TMP/rtapi_app.vg" 2>/dev/null && break; sleep 0.1; done
    if [ "$rc" -ne 0 ] || ! grep -q 'hm2_5i20.0: initialized virtual AnyIO board' "$TMP/session.out"; then
        echo "memcheck: HAL session failed (rc $rc)" >&2
        cat "$TMP/session.out" >&2
        fail=1
        return
    fi
    if grep -q 'ERROR SUMMARY: 0 errors' "$TMP/rtapi_app.vg"; then
        echo "memcheck: halrun session with hostmot2 + hm2_sim: clean ($(grep -o 'ERROR SUMMARY: [0-9]* errors' "$TMP/rtapi_app.vg"))"
    else
        echo "memcheck: halrun session with hostmot2 + hm2_sim: FAILED" >&2
        cat "$TMP/rtapi_app.vg" >&2
        fail=1
    fi
}

case "$WHAT" in
all) unit; session ;;
unit) unit ;;
session) session ;;
*) echo "usage: $0 [all|unit|session]" >&2; exit 2 ;;
esac
exit "$fail"
