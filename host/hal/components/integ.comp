// SPDX-License-Identifier: GPL-2.0-or-later
// integ: integrator with gain and windup limits, LinuxCNC 2.9's names and
// output (docs/integ.md).
component integ "Integrator with gain pin and windup limits";
pin in float in;
pin in float gain = 1.0;
pin out float out "Integral of gain * in since reset was last TRUE";
pin in bit reset "TRUE: out is held at 0";
pin in float max_ = 1e20;
pin in float min_ = -1e20;
function _;
license "GPL";
;;
if (reset) {
    out = 0;
} else {
    double v = out + in * gain * fperiod;
    if (v > max_)
        v = max_;
    if (v < min_)
        v = min_;
    out = v;
}
