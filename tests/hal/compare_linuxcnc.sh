#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# Dev tool: run the same .hal file through LinuxCNC 2.9's halrun (the
# behaviour reference, when installed) and through ours, normalize both
# (tests/hal/halnorm.py) and diff.  stdout and stderr are merged.
#   tests/hal/compare_linuxcnc.sh [halrun options] file.hal
# Exit 0 when identical.  Never used by `make test`.
here=$(cd "$(dirname "$0")" && pwd)
ours=${HM_BUILD:-$here/../../build}/bin/halrun
[ -x /usr/bin/halrun ] || { echo "LinuxCNC halrun not installed"; exit 2; }
tmp=$(mktemp -d)
export RTAPI_UID=65534 RTAPI_FIFO_PATH=/tmp/.rtapi_fifo
for i in 1 2 3 4 5; do
    /usr/bin/halrun -U >/dev/null 2>&1
    /usr/lib/linuxcnc/realtime status >/dev/null 2>&1 || break
    sleep 0.5
done
/usr/bin/halrun "$@" > "$tmp/lcnc" 2>&1
HAL_INSTANCE=cmp$$ "$ours" "$@" > "$tmp/ours" 2>&1
python3 "$here/halnorm.py" < "$tmp/lcnc" > "$tmp/lcnc.n"
python3 "$here/halnorm.py" < "$tmp/ours" > "$tmp/ours.n"
diff -u --label linuxcnc --label ours "$tmp/lcnc.n" "$tmp/ours.n"
rc=$?
rm -rf "$tmp"
exit $rc
