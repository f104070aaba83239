// SPDX-License-Identifier: GPL-2.0-or-later
// limit1: clamp to [min, max], LinuxCNC 2.9's names (docs/limit1.md).
component limit1 "Limit the output signal to fall between min and max";
pin in float in;
pin out float out;
pin in float min_ = -1e20;
pin in float max_ = 1e20;
function _;
license "GPL";
;;
double v = in;
if (v < min_)
    v = min_;
if (v > max_)
    v = max_;
out = v;
