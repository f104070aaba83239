#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# bench/pluto: Pluto-P firmware figures (EPP traffic per servo cycle, PWM
# frequency, max step rate, watchdog time) on the Verilated firmware.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
# shellcheck source=/dev/null
source "$ROOT/scripts/env.sh"
exec python "$ROOT/bench/pluto/bench_pluto.py"
