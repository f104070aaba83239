// SPDX-License-Identifier: GPL-2.0-or-later
// and2: two-input AND gate, LinuxCNC 2.9's names (docs/and2.md).
component and2 "Two-input AND gate";
pin in bit in0;
pin in bit in1;
pin out bit out "in0 AND in1";
function _ nofp;
license "GPL";
;;
out = in0 && in1;
