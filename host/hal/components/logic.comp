// SPDX-License-Identifier: GPL-2.0-or-later
// logic: AND/OR/XOR/NAND/NOR of up to 16 inputs chosen by the personality,
// LinuxCNC 2.9's names and personality bits (docs/logic.md):
//   bits 0-7  number of inputs (at most 16)
//   0x100 and, 0x200 or, 0x400 xor, 0x800 nand, 0x1000 nor.
component logic "Configurable logic gate: and, or, xor, nand, nor of up to 16 inputs";
pin in bit in-##[16 : personality & 0xff] "Input MM";
pin out bit and if personality & 0x100 "TRUE when every input is TRUE";
pin out bit or if personality & 0x200 "TRUE when any input is TRUE";
pin out bit xor if personality & 0x400 "TRUE when an odd number of inputs are TRUE";
pin out bit nand if personality & 0x800 "NOT and";
pin out bit nor if personality & 0x1000 "NOT or";
function _ nofp "Compute the enabled outputs from the inputs";
license "GPL";
;;
int n = personality & 0xff;
int all = 1, any = 0, odd = 0;
for (int i = 0; i < n; i++) {
    if (in(i)) {
        any = 1;
        odd = !odd;
    } else {
        all = 0;
    }
}
if (personality & 0x100)
    and = all;
if (personality & 0x200)
    or = any;
if (personality & 0x400)
    xor = odd;
if (personality & 0x800)
    nand = !all;
if (personality & 0x1000)
    nor = !any;
