// SPDX-License-Identifier: GPL-2.0-or-later
// or2: two-input OR gate, LinuxCNC 2.9's names (docs/or2.md).
component or2 "Two-input OR gate";
pin in bit in0;
pin in bit in1;
pin out bit out "in0 OR in1";
function _ nofp;
license "GPL";
;;
out = in0 || in1;
