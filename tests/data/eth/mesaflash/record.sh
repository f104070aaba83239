#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Records Debian's stock mesaflash talking to the virtual Ethernet boards
# (vboard --udp on loopback; no other network needed).  The boards serve at
# real-time priority (--udp-rt, needs root): mesaflash's probe gives the
# first reply only 2 ms (README.md).  Not part of
# `make test`: the outputs in this directory are what the tests compare
# against.  Run from the repository root after `make build`:
#   bash tests/data/eth/mesaflash/record.sh
set -euo pipefail
OUT=$(cd "$(dirname "$0")" && pwd)
VB=${HM_BUILD:-$PWD/build}/bin/vboard
FW=${HM_BUILD:-$PWD/build}/lib/firmware/hm2
TMP=$(mktemp -d)
trap 'kill $PID96 $PID92 2>/dev/null || true; rm -rf "$TMP"' EXIT
mesaflash --version > "$OUT/version.txt" 2>&1 || true

"$VB" --board 7i96s --firmware 7i96s_d --udp 127.0.0.2 --flash "$TMP/f96.bin" --udp-rt --log \
    > "$TMP/vb96.out" 2> "$TMP/vb96.err" &
PID96=$!
"$VB" --board 7i92 --firmware 7I76x2 --udp 127.0.0.3 --flash "$TMP/f92.bin" --udp-rt --log \
    > "$TMP/vb92.out" 2> "$TMP/vb92.err" &
PID92=$!
sleep 1
run() { # name, args...
    local name=$1
    shift
    { echo "\$ mesaflash $*"; mesaflash "$@" 2>&1; echo "[exit status $?]"; } > "$OUT/$name.txt" || true
}
run 7i96s-info --device 7i96s --addr 127.0.0.2
run 7i96s-verbose --device 7i96s --addr 127.0.0.2 --verbose
run 7i96s-readhmid --device 7i96s --addr 127.0.0.2 --readhmid
run 7i96s-print-pd --device 7i96s --addr 127.0.0.2 --print-pd
run 7i96s-rpo --device 7i96s --addr 127.0.0.2 --rpo 0x100
cp "$FW/7i96s/7i96s_d.BIT" "$FW/7i92/7I76x2.BIT" "$TMP/"
run 7i96s-write --device 7i96s --addr 127.0.0.2 --write "$TMP/7i96s_d.BIT"
run 7i96s-verify --device 7i96s --addr 127.0.0.2 --verify "$TMP/7i96s_d.BIT"
run 7i96s-write-fallback --device 7i96s --addr 127.0.0.2 --write "$TMP/7i96s_d.BIT" --fallback
run 7i96s-wrong-board --device 7i96s --addr 127.0.0.2 --write "$TMP/7I76x2.BIT"
run 7i96s-reload --device 7i96s --addr 127.0.0.2 --reload
sleep 1
run 7i96s-after-reload --device 7i96s --addr 127.0.0.2 --rpo 0x100
run 7i92-info --device 7i92 --addr 127.0.0.3
run 7i92-readhmid --device 7i92 --addr 127.0.0.3 --readhmid
run 7i92-write --device 7i92 --addr 127.0.0.3 --write "$TMP/7I76x2.BIT"
run 7i92-verify --device 7i92 --addr 127.0.0.3 --verify "$TMP/7I76x2.BIT"
run 7i92-reload --device 7i92 --addr 127.0.0.3 --reload
sleep 1
run 7i92-after-reload --device 7i92 --addr 127.0.0.3 --rpo 0x100
run 7i92-reset --device 7i92 --addr 127.0.0.3 --reset
# the datagrams as the boards logged them (first 24 bytes each)
grep -a "LBP16" "$TMP/vb96.err" | sed 's/ from 127.0.0.1:[0-9]*//' > "$OUT/7i96s-datagrams.log"
grep -a "LBP16" "$TMP/vb92.err" | sed 's/ from 127.0.0.1:[0-9]*//' > "$OUT/7i92-datagrams.log"
