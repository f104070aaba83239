#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Stock mesaflash's probe against the virtual 7i96S, with and without
# vboard --udp-rt (not part of `make test` or `make bench`: needs Debian's
# mesaflash and root).  mesaflash sends the IDROM-cookie read, sleeps 2 ms
# and looks once for the reply; on a loaded machine an ordinary-priority
# board process sometimes misses that window ("No 7I96S board found").
# Prints, per board, how many of N runs failed that way.
#   bash bench/eth/mesaflash_probe.sh [N]     (default 200)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
VB=${HM_BUILD:-$ROOT/build}/bin/vboard
N=${1:-200}
command -v mesaflash > /dev/null || { echo "mesaflash is not installed" >&2; exit 1; }
RT_IP=127.97.0.2 PLAIN_IP=127.97.0.3
"$VB" --board 7i96s --firmware 7i96s_d --udp $RT_IP --udp-rt > /dev/null &
RT_PID=$!
"$VB" --board 7i96s --firmware 7i96s_d --udp $PLAIN_IP > /dev/null &
PLAIN_PID=$!
trap 'kill $RT_PID $PLAIN_PID 2> /dev/null || true' EXIT
sleep 2
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
for ip in $RT_IP $PLAIN_IP; do
    fail=0
    for _ in $(seq "$N"); do
        case "$(mesaflash --device 7i96s --addr $ip 2>&1)" in
        *"No 7I96S board found"*) fail=$((fail + 1)) ;;
        esac
    done
    what=$([ $ip = $RT_IP ] && echo "--udp-rt" || echo "normal priority")
    echo "mesaflash --device 7i96s --addr $ip ($what): $fail of $N runs 'No 7I96S board found'"
done
