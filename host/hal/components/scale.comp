// SPDX-License-Identifier: GPL-2.0-or-later
// scale: gain and offset, LinuxCNC 2.9's names (docs/scale.md).
component scale "Applies a scale and offset to its input";
pin in float in;
pin in float gain;
pin in float offset;
pin out float out "out = in * gain + offset";
function _;
license "GPL";
;;
out = in * gain + offset;
