#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make lint`: every HDL file through Verilator --lint-only -Wall, Icarus and
# yosys (tests/lint/test_hdl_lint.py, one test per file and tool) and every
# Python file through black --check --line-length 100
# (tests/lint/test_python_format.py).  Both are part of `make test` too.
set -euo pipefail
cd "$(dirname "$0")/.."
exec python -m pytest -q tests/lint "$@"
