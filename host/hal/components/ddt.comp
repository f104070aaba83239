// SPDX-License-Identifier: GPL-2.0-or-later
// ddt: derivative, LinuxCNC 2.9's names (docs/ddt.md).
component ddt "Computes the derivative of the input function";
pin in float in;
pin out float out "(in - previous in) / period in seconds";
variable double old;
function _;
license "GPL";
;;
double v = in;
out = (v - old) / fperiod;
old = v;
