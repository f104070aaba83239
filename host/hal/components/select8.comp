// SPDX-License-Identifier: GPL-2.0-or-later
// select8: one-of-eight decoder, LinuxCNC 2.9's names (docs/select8.md).
component select8 "One-of-eight decoder";
pin in bit enable = TRUE "When FALSE, every output is FALSE";
pin in s32 sel "Number of the output to set TRUE (0 to 7)";
pin out bit out#[8] "TRUE when enable is TRUE and sel equals its number";
function _ nofp;
license "GPL";
;;
hal_s32_t s = sel;
int en = enable;
for (int i = 0; i < 8; i++)
    out(i) = en && s == i;
