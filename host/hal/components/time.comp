// SPDX-License-Identifier: GPL-2.0-or-later
// time: a cycle timer in hours, minutes and seconds, LinuxCNC 2.9's names
// (docs/time.md).
component time "Cycle timer: time in hours, minutes and seconds";
pin in bit start "Timing runs while TRUE (and pause is FALSE)";
pin in bit pause = 0 "TRUE pauses the timing";
pin out u32 seconds "Seconds (0-59)";
pin out u32 minutes "Minutes (0-59)";
pin out u32 hours "Hours";
variable double total;
variable int was_active;
function _;
license "GPL";
;;
int active = start || pause;
if (active && !was_active)
    total = 0;
if (start && !pause)
    total += fperiod;
was_active = active;
unsigned long long s = (unsigned long long)total;
seconds = (hal_u32_t)(s % 60);
minutes = (hal_u32_t)((s / 60) % 60);
hours = (hal_u32_t)(s / 3600);
