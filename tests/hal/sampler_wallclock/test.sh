#!/bin/bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Wall-clock overrun/underrun behaviour (LinuxCNC-style dropping); the
# exact counts depend on timing, so checkresult checks their relations.
cd "$(dirname "$0")"
build=${HM_BUILD:-$(cd ../../.. && pwd)/build}
env -u HAL_SIMCLOCK "$build/bin/halrun" -f wall.hal 2>&1
echo "exit $?"
