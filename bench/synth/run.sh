#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# bench/synth: yosys LUT/FF per module of the 5i20 SVST8_4 and 7i43 SVST4_4
# tops, nextpnr-ice40 fmax of a stepgen+encoder+pwmgen slice (synth.py);
# Pluto-P firmware size against the original and the EP1K10 (pluto_synth.py).
set -euo pipefail
cd "$(dirname "$0")"
PY=python3
[ -x ../../.venv/bin/python ] && PY=../../.venv/bin/python
"$PY" synth.py "$@"
echo
"$PY" pluto_synth.py
