// SPDX-License-Identifier: GPL-2.0-or-later
// constant: a parameter's value on a pin, LinuxCNC 2.9's names
// (docs/constant.md).
component constant "Use a parameter to set the value of a pin";
pin out float out;
param rw float value;
function _;
license "GPL";
;;
out = value;
