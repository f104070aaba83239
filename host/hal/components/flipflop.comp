// SPDX-License-Identifier: GPL-2.0-or-later
// flipflop: D flip-flop with set and reset, LinuxCNC 2.9's names
// (docs/flipflop.md).
component flipflop "D type flip-flop";
pin in bit data "Taken on a rising edge of clk";
pin in bit clk "Clock";
pin in bit set "TRUE forces out TRUE";
pin in bit reset "TRUE forces out FALSE (wins over set)";
pin io bit out "Output";
pin io bit out_not "Inverted output";
variable int last_clk;
function _ nofp;
license "GPL";
;;
int c = clk;
if (reset)
    out = 0;
else if (set)
    out = 1;
else if (c && !last_clk)
    out = data;
last_clk = c;
out_not = !out;
