// SPDX-License-Identifier: GPL-2.0-or-later
// not: inverter, LinuxCNC 2.9's names (docs/not.md).
component not "Inverter";
pin in bit in;
pin out bit out "NOT in";
function _ nofp;
license "GPL";
;;
out = !in;
