// SPDX-License-Identifier: GPL-2.0-or-later
// comp: two-input comparator with hysteresis, LinuxCNC 2.9's names and
// behaviour (docs/comp.md).  With d = in1 - in0 and h = hyst / 2:
// d > h sets out, d < -h clears it, anything else (also a nan input)
// keeps out and sets equal.
component comp "Two input comparator with hysteresis";
pin in float in0 "Inverting input";
pin in float in1 "Non-inverting input";
pin out bit out "TRUE when in1 > in0 (with hysteresis: see hyst)";
pin out bit equal "TRUE when in1 and in0 are within hyst/2 of each other";
param rw float hyst = 0.0 "Hysteresis: out switches at in1 - in0 = +hyst/2 and -hyst/2";
function _ "Update the comparator";
license "GPL";
;;
double d = in1 - in0;
double h = hyst / 2.0;
if (d > h) {
    out = 1;
    equal = 0;
} else if (d < -h) {
    out = 0;
    equal = 0;
} else {
    equal = 1;
}
