#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Dev tool: run the same .hal file through LinuxCNC 2.9's halrun (the
# behaviour reference, via lcnc-halrun) and through ours, normalize both
# (tests/hal/halnorm.py) and diff.  stdout and stderr are merged.
#   tests/hal/compare_linuxcnc.sh [halrun options] file.hal
# Exit 0 when identical.  Never used by `make test`.
here=$(cd "$(dirname "$0")" && pwd)
ours=${HM_BUILD:-$here/../../build}/bin/halrun
command -v lcnc-halrun > /dev/null || { echo "lcnc-halrun (LinuxCNC 2.9) not installed"; exit 2; }
tmp=$(mktemp -d)
# lcnc-halrun serializes LinuxCNC sessions (its shared-memory keys are fixed)
lcnc-halrun "$@" 2>&1 | grep -v "^Running with fallback_uid\|^Note: Using POSIX" > "$tmp/lcnc"
HAL_INSTANCE=cmp$$ "$ours" "$@" > "$tmp/ours" 2>&1
python3 "$here/halnorm.py" < "$tmp/lcnc" > "$tmp/lcnc.n"
python3 "$here/halnorm.py" < "$tmp/ours" > "$tmp/ours.n"
diff -u --label linuxcnc --label ours "$tmp/lcnc.n" "$tmp/ours.n"
rc=$?
rm -rf "$tmp"
exit $rc
