// SPDX-License-Identifier: GPL-2.0-or-later
// blend: linear interpolation between two inputs, LinuxCNC 2.9's names and
// output (docs/blend.md).
component blend "Perform linear interpolation between two values";
pin in float in1 "The output when select is 1";
pin in float in2 "The output when select is 0";
pin in float select "0..1 moves the output from in2 to in1";
pin out float out "The interpolated value";
param rw bit open "TRUE: select outside 0..1 extrapolates; FALSE: it is clamped to 0..1";
function _;
license "GPL";
;;
double s = select;
if (!open) {
    if (s < 0.0)
        s = 0.0;
    if (s > 1.0)
        s = 1.0;
}
out = in1 * s + in2 * (1.0 - s);
