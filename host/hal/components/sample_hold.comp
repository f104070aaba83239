// SPDX-License-Identifier: GPL-2.0-or-later
// sample_hold: s32 sample and hold, LinuxCNC 2.9's names
// (docs/sample_hold.md).
component sample_hold "Sample and hold an s32 value";
pin in s32 in "Value to sample";
pin in bit hold "TRUE: keep out; FALSE: out follows in";
pin out s32 out "The last value of in sampled while hold was FALSE";
function _ nofp;
license "GPL";
;;
if (!hold)
    out = in;
