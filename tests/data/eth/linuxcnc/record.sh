#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# LinuxCNC 2.9's own hm2_eth (linuxcnc-uspace, through lcnc-halrun) against
# the virtual 7i96S.  Not part of `make test` (needs root and LinuxCNC).
# hm2_eth reads the board's MAC over LBP16 and pins it as a static ARP entry
# (SIOCSARP) and edits iptables, so it runs in a network namespace of its
# own, joined by a veth pair to the board's namespace; the board-side veth
# carries the board's MAC (00:60:1B + the IP's low three bytes), as a real
# card's interface does.  Run from the repository root after `make build`.
set -euo pipefail
OUT=$(cd "$(dirname "$0")" && pwd)
VB=${HM_BUILD:-$PWD/build}/bin/vboard
NSB=hm2eb$$ NSH=hm2eh$$ VH=ve$$h VBD=ve$$b
cleanup() {
    [ -n "${PID:-}" ] && kill "$PID" 2>/dev/null || true
    ip netns del "$NSB" 2>/dev/null || true
    ip netns del "$NSH" 2>/dev/null || true
}
trap cleanup EXIT
ip netns add "$NSB"
ip netns add "$NSH"
ip link add "$VH" type veth peer name "$VBD"
ip link set "$VBD" netns "$NSB"
ip link set "$VH" netns "$NSH"
ip -n "$NSB" link set "$VBD" address 00:60:1b:a8:01:79
ip -n "$NSB" addr add 192.168.1.121/24 dev "$VBD"
ip -n "$NSH" addr add 192.168.1.1/24 dev "$VH"
for ns in "$NSB" "$NSH"; do ip -n "$ns" link set lo up; done
ip -n "$NSB" link set "$VBD" up
ip -n "$NSH" link set "$VH" up
ip netns exec "$NSB" "$VB" --board 7i96s --firmware 7i96s_d --udp 192.168.1.121 &
PID=$!
sleep 1
ip netns exec "$NSH" lcnc-halrun -f "$OUT/hm2_eth-7i96s.hal" > "$OUT/hm2_eth-7i96s.out" 2>&1
ip netns exec "$NSB" "$(dirname "$VB")/../../.venv/bin/python" -c "
import sys; sys.path.insert(0, 'tests/common'); import lbp16
print(lbp16.Lbp16Client('192.168.1.121').status())" > "$OUT/board-status-after.txt" || true
