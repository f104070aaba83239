#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Records Debian's stock mesaflash --readhmid against the virtual Ethernet
# boards of this build (vboard --udp on loopback), for
# tests/flash/test_hm2flash_readhmid.py.  Not part of `make test` (the tests
# never run mesaflash).  Run from the repository root after `make build`:
#   bash tests/flash/data/record.sh
set -euo pipefail
OUT=$(cd "$(dirname "$0")" && pwd)
VB=${HM_BUILD:-$PWD/build}/bin/vboard
TMP=$(mktemp -d)
trap 'kill $PID96 $PID92 2>/dev/null || true; rm -rf "$TMP"' EXIT
mesaflash --version > "$OUT/mesaflash-version.txt" 2>&1 || true
"$VB" --board 7i96s --firmware 7i96s_d --udp 127.0.96.5 --socket "$TMP/a.sock" > /dev/null 2>&1 &
PID96=$!
"$VB" --board 7i92 --firmware 7I76x2 --udp 127.0.92.5 --socket "$TMP/b.sock" > /dev/null 2>&1 &
PID92=$!
sleep 1
run() { # name, args...  (mesaflash's probe sometimes misses a loaded board: try again)
    local name=$1
    shift
    for _ in 1 2 3 4 5; do
        { echo "\$ mesaflash $*"; mesaflash "$@" 2>&1; echo "[exit status $?]"; } > "$OUT/$name.txt" || true
        grep -q "board found" "$OUT/$name.txt" || return 0
        sleep 0.5
    done
}
run mesaflash-7i92-readhmid --device 7i92 --addr 127.0.92.5 --readhmid
run mesaflash-7i96s-readhmid --device 7i96s --addr 127.0.96.5 --readhmid
