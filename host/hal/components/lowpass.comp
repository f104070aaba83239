// SPDX-License-Identifier: GPL-2.0-or-later
// lowpass: first-order low-pass filter, LinuxCNC 2.9's names
// (docs/lowpass.md).
component lowpass "Low-pass filter";
pin in float in;
pin out float out "out += (in - out) * gain; out = in while load is TRUE";
pin in bit load;
param rw float gain;
function _;
license "GPL";
;;
if (load)
    out = in;
else
    out += (in - out) * gain;
