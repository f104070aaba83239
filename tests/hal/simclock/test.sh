# SPDX-License-Identifier: GPL-2.0-or-later
# Run the same file twice on the simulated clock (option -S and the
# environment variable): both runs must print the same thing; checkresult
# compares the numbers with a model of the schedule.
set -e
halrun -S -f sim.hal > run1.tmp
HAL_SIMCLOCK=1 halrun -f sim.hal > run2.tmp
cmp run1.tmp run2.tmp && echo "identical"
cat run1.tmp
rm -f run1.tmp run2.tmp
