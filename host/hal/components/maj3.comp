// SPDX-License-Identifier: GPL-2.0-or-later
// maj3: majority of three bits, optionally inverted, LinuxCNC 2.9's names
// (docs/maj3.md).
component maj3 "Majority of three inputs";
pin in bit in1;
pin in bit in2;
pin in bit in3;
pin out bit out "TRUE when at least two inputs are TRUE (inverted if invert)";
param rw bit invert "Invert the output";
function _ nofp;
license "GPL";
;;
int n = (in1 != 0) + (in2 != 0) + (in3 != 0);
out = (n >= 2) != (invert != 0);
