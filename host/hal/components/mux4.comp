// SPDX-License-Identifier: GPL-2.0-or-later
// mux4: one of four float inputs, chosen by two select bits, LinuxCNC 2.9's
// names (docs/mux4.md).
component mux4 "Select one of four float inputs";
pin in bit sel0 "Select bit 0 (weight 1)";
pin in bit sel1 "Select bit 1 (weight 2)";
pin out float out "The input numbered sel1*2 + sel0";
pin in float in0;
pin in float in1;
pin in float in2;
pin in float in3;
function _;
license "GPL";
;;
if (sel1)
    out = sel0 ? in3 : in2;
else
    out = sel0 ? in1 : in0;
