// SPDX-License-Identifier: GPL-2.0-or-later
// clarke3: Clarke transform of three phases, LinuxCNC 2.9's names and output
// (docs/clarke3.md).
component clarke3 "Clarke (3 phase to cartesian) transform";
pin in float a;
pin in float b;
pin in float c "The three phases";
pin out float x;
pin out float y "Cartesian components of the output";
pin out float h "Homopolar component: sqrt(2)/3 x (a + b + c)";
function _;
license "GPL";
;;
FUNCTION(_) {
    // constants to 15 digits, as 2.9 rounds them; h is sqrt(2)/3 of the sum
    x = 0.666666666666667 * a - 0.333333333333333 * (b + c);
    y = 0.577350269189626 * (b - c);
    h = 0.471404520791032 * (a + b + c);
}
