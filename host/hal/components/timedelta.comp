// SPDX-License-Identifier: GPL-2.0-or-later
// timedelta: measures the time between runs of its function against the
// thread period (scheduling jitter), LinuxCNC 2.9's names and behaviour
// (docs/timedelta.md).  The first run only takes the time; the second
// sets out, min, max and the error sums but not the jitter pins; from the
// third on every pin follows.  reset TRUE clears jitter, max and out and
// starts over (min, err and avg-err go on).
component timedelta "Measure thread scheduling timing";
pin out s32 jitter = 0 "Largest |current-error| so far (ns)";
pin out s32 current_jitter = 0 "|current-error| of this run (ns)";
pin out s32 current_error = 0 "Time since the previous run minus the period (ns)";
pin out s32 min_ = 0 "Shortest time between runs (ns)";
pin out s32 max_ = 0 "Longest time between runs (ns)";
pin in bit reset "TRUE: clear jitter, max and out and start over";
pin out s32 out "Time since the previous run (ns)";
pin out s32 err = 0 "Sum of the errors (time between runs minus period, ns)";
pin out float avg_err = 0 "Average error per run (ns)";
variable long long last;
variable int runs;
variable long long count = 1;
variable long long worst;
function _ nofp;
license "GPL";
;;
long long now = rtapi_get_time();
if (runs == 0) {
    /* first run (again after a reset): only take the time */
    last = now;
    if (!reset)
        runs = 1;
    return;
}
long long del = now - last;
long long e = del - period;
last = now;
out = (hal_s32_t)del;
err = (hal_s32_t)((uint32_t)err + (uint32_t)e);
count++;
avg_err = (double)err / (double)count;
if (runs == 1) {
    min_ = (hal_s32_t)del;
    max_ = (hal_s32_t)del;
    worst = e < 0 ? -e : e;
    runs = 2;
} else {
    long long j = e < 0 ? -e : e;
    current_error = (hal_s32_t)e;
    current_jitter = (hal_s32_t)j;
    if (j > worst)
        worst = j;
    jitter = (hal_s32_t)worst;
    if (del < min_)
        min_ = (hal_s32_t)del;
    if (del > max_)
        max_ = (hal_s32_t)del;
}
if (reset) {
    jitter = 0;
    max_ = 0;
    out = 0;
    runs = 0;
}
