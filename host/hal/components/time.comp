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
variable int in_cycle;
function _;
license "GPL";
;;
/* A cycle starts when timing starts (start TRUE, pause FALSE) with no
 * cycle in progress, and ends when start and pause are both FALSE; pause
 * holds the time within a cycle, even if start drops meanwhile (LinuxCNC
 * 2.9's behaviour, measured with sampler). */
if (start && !pause) {
    if (!in_cycle) {
        total = 0;
        in_cycle = 1;
    }
    total += fperiod;
} else if (!start && !pause) {
    in_cycle = 0;
}
unsigned long long s = (unsigned long long)total;
seconds = (hal_u32_t)(s % 60);
minutes = (hal_u32_t)((s / 60) % 60);
hours = (hal_u32_t)(s / 3600);
