// SPDX-License-Identifier: GPL-2.0-or-later
// sum2: weighted sum of two inputs, LinuxCNC 2.9's names (docs/sum2.md).
component sum2 "Sum of two inputs (each with a gain) and an offset";
pin in float in0;
pin in float in1;
pin out float out "out = in0 * gain0 + in1 * gain1 + offset";
param rw float gain0 = 1.0;
param rw float gain1 = 1.0;
param rw float offset = 0.0;
function _;
license "GPL";
;;
out = in0 * gain0 + in1 * gain1 + offset;
