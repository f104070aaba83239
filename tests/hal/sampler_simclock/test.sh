#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Run sim.hal on the simulated clock (halrun -S); checkresult compares the
# sampled file with in.txt and the counters with their exact values.
cd "$(dirname "$0")"
build=${HM_BUILD:-$(cd ../../.. && pwd)/build}
rm -f out.txt
"$build/bin/halrun" -S -f sim.hal 2>&1
echo "exit $?"
# halsampler had read all 1000 samples when simrun returned (the sampler
# waits for it); give it a moment to write them out and exit.
for i in $(seq 50); do
    [ "$(wc -l < out.txt 2>/dev/null)" = 1000 ] && break
    sleep 0.1
done
echo "--- out.txt"
cat out.txt 2>/dev/null
rm -f out.txt
