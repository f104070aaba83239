// SPDX-License-Identifier: GPL-2.0-or-later
// mult2: product of two inputs, LinuxCNC 2.9's names (docs/mult2.md).
component mult2 "Product of two inputs";
pin in float in0;
pin in float in1;
pin out float out "out = in0 * in1";
function _;
license "GPL";
;;
out = in0 * in1;
