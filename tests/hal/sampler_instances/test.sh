#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Session isolation: two halrun sessions at once, HAL_INSTANCE <inst>-a and
# <inst>-b, both with sampler/streamer channel 0.  Each must get exactly
# its own input back, and no shared-memory object of either may be left.
cd "$(dirname "$0")"
build=${HM_BUILD:-$(cd ../../.. && pwd)/build}
base=${HAL_INSTANCE:-iso$$}
rm -f out_a.txt out_b.txt
HAL_INSTANCE=$base-a "$build/bin/halrun" -S -f iso_a.hal > log_a.txt 2>&1 &
pa=$!
HAL_INSTANCE=$base-b "$build/bin/halrun" -S -f iso_b.hal > log_b.txt 2>&1 &
pb=$!
wait $pa; echo "a: exit $?"; cat log_a.txt
wait $pb; echo "b: exit $?"; cat log_b.txt
for x in a b; do
    for i in $(seq 50); do
        [ "$(wc -l < out_$x.txt 2>/dev/null)" = 300 ] && break
        sleep 0.1
    done
    if cmp -s in_$x.txt <(sed 's/ $//' out_$x.txt); then echo "$x: data ok"; else echo "$x: data differs"; fi
done
sleep 0.2
echo "left in /dev/shm: $(ls /dev/shm | grep -c -- "-$base-[ab]")"
for x in a b; do HAL_INSTANCE=$base-$x "$build/bin/halrun" -U > /dev/null 2>&1; done
rm -f out_a.txt out_b.txt log_a.txt log_b.txt
