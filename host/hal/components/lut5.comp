// SPDX-License-Identifier: GPL-2.0-or-later
// lut5: any logic function of five bits by look-up table, LinuxCNC 2.9's
// names (docs/lut5.md).  Bit k of `function` is the output for the input
// combination whose binary value (in-4 .. in-0) is k.
component lut5 "Arbitrary 5-input logic function from a look-up table";
pin in bit in-#[5] "Input bit #";
pin out bit out "Bit (in-4 in-3 in-2 in-1 in-0) of function";
param rw u32 function_ "The truth table: bit k is the output for inputs of value k";
function _ nofp;
license "GPL";
;;
unsigned k = (in(0) ? 1u : 0u) | (in(1) ? 2u : 0u) | (in(2) ? 4u : 0u) | (in(3) ? 8u : 0u) |
             (in(4) ? 16u : 0u);
out = (function_ >> k) & 1u;
