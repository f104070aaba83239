// SPDX-License-Identifier: GPL-2.0-or-later
// mux8: one of eight float inputs, chosen by three select bits, LinuxCNC
// 2.9's names (docs/mux8.md).
component mux8 "Select one of eight float inputs";
pin in bit sel0 "Select bit 0 (weight 1)";
pin in bit sel1 "Select bit 1 (weight 2)";
pin in bit sel2 "Select bit 2 (weight 4)";
pin out float out "The input numbered sel2*4 + sel1*2 + sel0";
pin in float in#[8];
function _;
license "GPL";
;;
int n = (sel0 ? 1 : 0) | (sel1 ? 2 : 0) | (sel2 ? 4 : 0);
out = in(n);
