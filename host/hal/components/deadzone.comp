// SPDX-License-Identifier: GPL-2.0-or-later
// deadzone: the centre while within the dead zone, LinuxCNC 2.9's names and
// output (docs/deadzone.md).
component deadzone "Return the center if within the threshold";
param rw float center = 0.0 "Middle of the dead zone";
param rw float threshold = 1.0 "Width of the dead zone (center +- threshold/2)";
pin in float in;
pin out float out;
function _ "Update out from in and the parameters";
license "GPL";
;;
double half = threshold / 2.0;
if (in < center - half)
    out = in + half;
else if (in > center + half)
    out = in - half;
else
    out = center;
