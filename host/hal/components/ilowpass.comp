// SPDX-License-Identifier: GPL-2.0-or-later
// ilowpass: low-pass filter with integer input and output, LinuxCNC 2.9's
// names and output (docs/ilowpass.md).
component ilowpass "Low-pass filter with integer inputs and outputs";
pin in s32 in;
pin out s32 out "in * scale through a low-pass filter, rounded";
param rw float scale = 1024 "Factor applied to in before filtering";
param rw float gain = .5 "Fraction of the remaining way the filter moves each period";
variable double value;
function _ "Update out from in and the parameters";
license "GPL";
;;
#include <rtapi_math.h>
FUNCTION(_) {
    double r;
    value += (in * scale - value) * gain;
    r = floor(value + .5);
    // to 64 bits (out of range or NaN: INT64_MIN, as x86 converts), then
    // the low 32 bits: 2.9's result when value leaves the s32 range
    rtapi_s64 w = (r >= -9223372036854775808.0 && r < 9223372036854775808.0)
                      ? (rtapi_s64)r : INT64_MIN;
    out = (rtapi_s32)(rtapi_u32)(rtapi_u64)w;
}
