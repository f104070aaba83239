// SPDX-License-Identifier: GPL-2.0-or-later
// xor2: two-input XOR gate, LinuxCNC 2.9's names (docs/xor2.md).
component xor2 "Two-input XOR (exclusive OR) gate";
pin in bit in0;
pin in bit in1;
pin out bit out "in0 XOR in1";
function _ nofp;
license "GPL";
;;
out = (in0 != 0) != (in1 != 0);
