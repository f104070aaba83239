// SPDX-License-Identifier: GPL-2.0-or-later
// feedcomp: scale an input by velocity / feed rate, LinuxCNC 2.9's names and
// output (docs/feedcomp.md).
component feedcomp "Multiply the input by the ratio of current velocity to the feed rate.";
pin out float out "in * vel / feed when enabled, else in";
pin in float in "The value to scale";
pin in bit enable "TRUE: compensate; FALSE: out = in";
pin in float vel "The current velocity";
param rw float feed "The feed rate at which out = in";
function _;
license "GPL";
;;
if (enable)
    out = in * (vel / feed);
else
    out = in;
