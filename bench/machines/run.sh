#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# bench/machines: what the machine models (vboard --machine) cost.  The
# lockstep cost of one 1 ms servo cycle (the driver's read and write
# bursts, 1 ms of board time) on a virtual 5i20 running SVST8_4 with three
# PWM-driven servo axes, with the servo mill's machine behind the pins and
# without; anchor: the models add <= 5 %.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
. "$root/scripts/env.sh"
exec python "$here/machbench.py" "$@"
