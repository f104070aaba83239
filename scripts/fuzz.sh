#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make fuzz`: the fuzz tests for longer than `make test` gives them
# (HM_FUZZ_SECONDS per target, default 60).
set -euo pipefail
cd "$(dirname "$0")/.."
export HM_FUZZ_SECONDS="${HM_FUZZ_SECONDS:-60}"
exec python -m pytest -q tests/fuzz "$@"
