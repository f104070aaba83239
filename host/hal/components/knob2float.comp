// SPDX-License-Identifier: GPL-2.0-or-later
// knob2float: counts (from an encoder) to a float within limits, LinuxCNC
// 2.9's names and output (docs/knob2float.md).
component knob2float "Convert counts (probably from an encoder) to a float value";
pin in s32 counts "Counts";
pin in bit enable "TRUE: out changes with counts; FALSE: out stays";
pin in float scale "Change of out per count";
pin out float out "Output value";
param rw float max_out = 1.0 "Largest output; more counts are ignored";
param rw float min_out = 0.0 "Smallest output; fewer counts are ignored";
variable rtapi_s32 old_counts;
function _;
license "GPL";
;;
// the count change in 64 bits: a jump across the s32 range is a big change
rtapi_s64 delta = (rtapi_s64)counts - old_counts;
old_counts = counts;
if (enable) {
    double v = out + delta * scale;
    if (v < min_out)
        v = min_out;
    if (v > max_out)
        v = max_out;
    out = v;
}
