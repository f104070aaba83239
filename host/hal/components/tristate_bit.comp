// SPDX-License-Identifier: GPL-2.0-or-later
// tristate_bit: drives its I/O output only while enabled, like a tristate
// buffer on a shared line; LinuxCNC 2.9's names (docs/tristate_bit.md).
component tristate_bit "Put a bit on an I/O pin only while enabled";
pin in bit in "Value to drive";
pin io bit out "Driven with in while enable is TRUE, left alone otherwise";
pin in bit enable "TRUE: drive out";
function _ nofp "If enable is TRUE, copy in to out";
license "GPL";
;;
if (enable)
    out = in;
