// SPDX-License-Identifier: GPL-2.0-or-later
// match8: TRUE when two 8-bit words given as bits are equal and the
// cascade input is TRUE, LinuxCNC 2.9's names (docs/match8.md).
component match8 "8-bit binary match detector";
pin in bit in = TRUE "Cascade input: when FALSE, out is FALSE";
pin in bit a0;
pin in bit a1;
pin in bit a2;
pin in bit a3;
pin in bit a4;
pin in bit a5;
pin in bit a6;
pin in bit a7;
pin in bit b0;
pin in bit b1;
pin in bit b2;
pin in bit b3;
pin in bit b4;
pin in bit b5;
pin in bit b6;
pin in bit b7;
pin out bit out "TRUE when in is TRUE and a0..a7 equal b0..b7";
function _ nofp;
license "GPL";
;;
int differ = (a0 != b0) | (a1 != b1) | (a2 != b2) | (a3 != b3) | (a4 != b4) | (a5 != b5) |
             (a6 != b6) | (a7 != b7);
out = in && !differ;
