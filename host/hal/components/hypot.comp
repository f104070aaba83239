// SPDX-License-Identifier: GPL-2.0-or-later
// hypot: Euclidean length of three inputs, LinuxCNC 2.9's names and output
// (docs/hypot.md).
component hypot "Three-input hypotenuse (Euclidean distance) calculator";
pin in float in0;
pin in float in1;
pin in float in2;
pin out float out "sqrt(in0^2 + in1^2 + in2^2)";
function _;
license "GPL";
;;
#include <rtapi_math.h>
FUNCTION(_) {
    out = sqrt(in0 * in0 + in1 * in1 + in2 * in2);
}
