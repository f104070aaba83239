#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# `make test`: the C unit tests (ctest), then every pytest test under tests/
# with the skip guard (tests/common/skipguard.py, tests/skips.txt), then the
# per-area counts (scripts/test_summary.py) as the last lines, so an area
# that lost its tests is visible and fails the run.
#   HM_BUILD     build tree (set by the Makefile)
#   JOBS         ctest parallelism
#   PYTEST_ARGS  extra pytest arguments; when set (a narrowed run) an area
#                without tests is reported but not an error
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${HM_BUILD:-$root/build}
jobs=${JOBS:-$(nproc)}
report=$(mktemp -d)
trap 'rm -rf "$report"' EXIT

(cd "$build" && ctest --output-on-failure -j "$jobs" --output-junit "$report/ctest.xml")
ctest_rc=$?

# PYTEST_ARGS is shell words, quotes respected (e.g. -k 'a or b').
eval "pytest_args=(${PYTEST_ARGS:-})"
(cd "$root" && python -m pytest --area-report="$report/areas.json" "${pytest_args[@]}" tests)
pytest_rc=$?

narrowed=()
[ -n "${PYTEST_ARGS:-}" ] && narrowed=(--narrowed)
python "$root/scripts/test_summary.py" --tests "$root/tests" --ctest "$report/ctest.xml" \
    --areas "$report/areas.json" --ctest-rc "$ctest_rc" --pytest-rc "$pytest_rc" "${narrowed[@]}"
