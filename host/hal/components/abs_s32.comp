// SPDX-License-Identifier: GPL-2.0-or-later
// abs_s32: absolute value and sign of an s32, LinuxCNC 2.9's names
// (docs/abs_s32.md).
component abs_s32 "Compute the absolute value and sign of an s32 input";
pin in s32 in;
pin out s32 out "|in|; -2147483648 stays -2147483648 (two's complement)";
pin out bit sign "TRUE when in is negative";
pin out bit is_positive "TRUE when in > 0";
pin out bit is_negative "TRUE when in < 0";
function _ nofp;
license "GPL";
;;
rtapi_s32 v = in;
if (v >= 0) {
    sign = 0;
    out = v;
} else {
    sign = 1;
    out = (rtapi_s32)(0u - (rtapi_u32)v); /* no signed overflow at INT32_MIN */
}
is_positive = v > 0;
is_negative = v < 0;
