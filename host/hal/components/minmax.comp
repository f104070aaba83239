// SPDX-License-Identifier: GPL-2.0-or-later
// minmax: running maximum and minimum of the input, LinuxCNC 2.9's names and
// output (docs/minmax.md).
component minmax "Track the minimum and maximum values of the input to the outputs";
pin in float in;
pin in bit reset "TRUE: max and min are set to in";
pin out float max_;
pin out float min_;
function _;
license "GPL";
;;
if (reset) {
    max_ = in;
    min_ = in;
} else {
    if (in > max_)
        max_ = in;
    if (in < min_)
        min_ = in;
}
