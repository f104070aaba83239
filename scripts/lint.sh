#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make lint`: every HDL file through Verilator --lint-only -Wall, Icarus and
# yosys (tests/lint/test_hdl_lint.py, one test per file and tool) and every
# Python file through black --check --line-length 100 and the annotation
# check (tests/lint/test_python_{format,types}.py).  All part of `make test`.
set -euo pipefail
cd "$(dirname "$0")/.."
exec python -m pytest -q tests/lint "$@"
