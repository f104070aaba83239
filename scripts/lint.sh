#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make lint`: every HDL file through Verilator --lint-only -Wall, Icarus and
# yosys (tests/lint/test_hdl_lint.py does the work, one test per file and tool).
set -euo pipefail
cd "$(dirname "$0")/.."
exec python -m pytest -q tests/lint "$@"
