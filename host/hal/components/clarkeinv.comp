// SPDX-License-Identifier: GPL-2.0-or-later
// clarkeinv: rotation and inverse Clarke transform, LinuxCNC 2.9's names and
// output (docs/clarkeinv.md).
component clarkeinv "Inverse Clarke transform";
pin in float x;
pin in float y "Cartesian components of the input";
pin in float h "Homopolar component (usually 0); each phase gets h / sqrt(2)";
pin in float theta "Rotation angle: 0..1 is 0..360 degrees";
pin out float a;
pin out float b;
pin out float c "The three phases";
function _;
license "GPL";
;;
#include <rtapi_math.h>
FUNCTION(_) {
    // 2.9's constants: 2 pi to 10 digits, sqrt(3)/2 and 1/sqrt(2) to 15
    double ang = theta * 6.283185308;
    double s = sin(ang), co = cos(ang);
    double xr = x * co - y * s;
    double yr = x * s + y * co;
    double hh = 0.707106781186547 * h;
    a = xr + hh;
    b = -0.5 * xr + 0.866025403784439 * yr + hh;
    c = -0.5 * xr - 0.866025403784439 * yr + hh;
}
