// SPDX-License-Identifier: GPL-2.0-or-later
// limit2: clamp and slew-rate limit, LinuxCNC 2.9's names (docs/limit2.md).
component limit2 "Limit the output signal to fall between min and max and limit its slew rate to less than maxv per second";
pin in float in;
pin out float out;
pin in bit load "TRUE: out follows in (clamped) without the slew limit";
pin in float min_ = -1e20;
pin in float max_ = 1e20;
pin in float maxv = 1e20;
variable double old;
function _;
license "GPL";
;;
double v = in;
if (v < min_)
    v = min_;
if (v > max_)
    v = max_;
if (!load) {
    double step = maxv * fperiod;
    if (v > old + step)
        v = old + step;
    if (v < old - step)
        v = old - step;
}
old = v;
out = v;
