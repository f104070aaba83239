#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Bad module parameters: each line of cases.txt is loaded in its own
# session (after `loadrt not names=clash` for a name collision), followed
# by `show comp` and `show pin`, so checkresult can see the error and that
# nothing of the failed module was left behind.
cd "$(dirname "$0")"
build=${HM_BUILD:-$(cd ../../.. && pwd)/build}
while IFS= read -r line; do
    printf 'loadrt not names=clash\n%s\nshow comp\nshow pin\n' "$line" > case.hal
    echo "=== $line"
    "$build/bin/halrun" -k -f case.hal 2>&1
    echo "exit $?"
done < cases.txt
rm -f case.hal
