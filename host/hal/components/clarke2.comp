// SPDX-License-Identifier: GPL-2.0-or-later
// clarke2: two-input Clarke transform (a + b + c = 0), LinuxCNC 2.9's names
// and output (docs/clarke2.md).
component clarke2 "Two input version of Clarke transform";
pin in float a;
pin in float b "Two phases of a three-phase input whose phases sum to 0";
pin out float x;
pin out float y "Cartesian components of the output";
function _;
license "GPL";
;;
FUNCTION(_) {
    x = a;
    // 1/sqrt(3) and 2/sqrt(3) to 15 digits, as 2.9 rounds them
    y = 0.577350269189626 * a + 1.15470053837925 * b;
}
