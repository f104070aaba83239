// SPDX-License-Identifier: GPL-2.0-or-later
// bitwise: six bitwise operations on two u32 words, LinuxCNC 2.9's names
// (docs/bitwise.md).
component bitwise "Bitwise AND, OR, XOR and their inverses of two u32 inputs";
pin in u32 in0 "First operand";
pin in u32 in1 "Second operand";
pin out u32 out_and "in0 AND in1";
pin out u32 out_or "in0 OR in1";
pin out u32 out_xor "in0 XOR in1";
pin out u32 out_nand "NOT (in0 AND in1)";
pin out u32 out_nor "NOT (in0 OR in1)";
pin out u32 out_xnor "NOT (in0 XOR in1)";
function _ nofp;
license "GPL";
;;
hal_u32_t a = in0;
hal_u32_t b = in1;
out_and = a & b;
out_or = a | b;
out_xor = a ^ b;
out_nand = ~(a & b);
out_nor = ~(a | b);
out_xnor = ~(a ^ b);
