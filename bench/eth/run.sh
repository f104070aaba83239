#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Ethernet boards (not part of `make test`): the servo-cycle round trip over
# loopback UDP against the virtual 7i96S (one read datagram with its reply,
# one write datagram, as hm2_eth sends them per period), next to the anchor
# (hm2_eth on real hardware ~104 us; goal <= 50 us here).  See roundtrip.py.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
source "$ROOT/scripts/env.sh"
python "$ROOT/bench/eth/roundtrip.py" "${1:-2000}"
