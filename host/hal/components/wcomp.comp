// SPDX-License-Identifier: GPL-2.0-or-later
// wcomp: window comparator, LinuxCNC 2.9's names (docs/wcomp.md).
component wcomp "Window comparator";
pin in float in "Value being compared";
pin in float min_ "Lower edge of the window";
pin in float max_ "Upper edge of the window";
pin out bit out "TRUE when in is neither under nor over";
pin out bit under "TRUE when in <= min";
pin out bit over "TRUE when in >= max";
function _;
license "GPL";
;;
double v = in;
double lo = min_;
double hi = max_;
under = v <= lo;
over = v >= hi;
/* neither under nor over (so a nan input counts as inside, as in 2.9) */
out = !(v <= lo) && !(v >= hi);
