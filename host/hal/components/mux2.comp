// SPDX-License-Identifier: GPL-2.0-or-later
// mux2: select one of two inputs, LinuxCNC 2.9's names (docs/mux2.md).
component mux2 "Select from one of two input values";
pin in bit sel;
pin out float out "Follows in0 when sel is FALSE, in1 when sel is TRUE";
pin in float in1;
pin in float in0;
function _;
license "GPL";
;;
out = sel ? in1 : in0;
