#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Bad load options of pid, stepgen, encoder, pwmgen and steptest: each
# line of cases.txt is loaded in its own session, followed by `show comp`
# and `show pin`, so checkresult can see the error and that nothing of the
# failed module was left behind.  Then one session where stepgen's maxvel
# is set above what the timing allows, twice: the message comes once.
cd "$(dirname "$0")"
build=${HM_BUILD:-$(cd ../../.. && pwd)/build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
while IFS= read -r line; do
    printf '%s\nshow comp\nshow pin\n' "$line" > "$tmp/case.hal"
    echo "=== $line"
    "$build/bin/halrun" -k -f "$tmp/case.hal" 2>&1
    echo "exit $?"
done < cases.txt
cat > "$tmp/maxvel.hal" <<'HAL'
loadrt threads name1=t period1=1000000
loadrt stepgen step_type=0,2 ctrl_type=v,v
addf stepgen.update-freq t
addf stepgen.make-pulses t
setp stepgen.0.maxvel 2000
setp stepgen.1.maxvel 1000
setp stepgen.1.position-scale 3
setp stepgen.0.enable 1
setp stepgen.1.enable 1
simrun 5ms
setp stepgen.0.maxvel 3000
simrun 5ms
getp stepgen.0.maxvel
getp stepgen.1.maxvel
HAL
echo "=== maxvel"
"$build/bin/halrun" -S -f "$tmp/maxvel.hal" 2>&1
echo "exit $?"
