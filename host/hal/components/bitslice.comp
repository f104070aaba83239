// SPDX-License-Identifier: GPL-2.0-or-later
// bitslice: the bits of a u32 word on separate bit pins; the personality
// is the number of bits (0 to 32), LinuxCNC 2.9's names (docs/bitslice.md).
component bitslice "Split a u32 word into bit outputs";
pin in u32 in "The word to split";
pin out bit out-##[32 : personality] "Bit MM of in";
function _ nofp;
license "GPL";
;;
hal_u32_t w = in;
for (int i = 0; i < personality; i++)
    out(i) = (w >> i) & 1u;
