// SPDX-License-Identifier: GPL-2.0-or-later
// joyhandle: nonlinear joystick curve with dead band, scale and offset,
// LinuxCNC 2.9's names and output (docs/joyhandle.md).
component joyhandle "sets nonlinear joypad movements, deadbands and scales";
pin in float in "Joystick position, -1..1";
pin out float out "scale * f(in) + offset, point-symmetric";
param rw float power = 2.0 "Exponent of the curve (set back to 1 when lower)";
param rw float deadband = 0. "Inputs within +-deadband give 0 (kept within 0..0.99)";
param rw float scale = 1. "Output at full deflection, less offset";
param rw float offset = 0. "Output just outside the dead band";
param rw bit inverse = 0 "TRUE: the mirrored (progressive) curve";
function _;
license "GPL";
;;
#include <rtapi_math.h>
FUNCTION(_) {
    double ax = fabs(in), u, f, y;
    if (power < 1.0)
        power = 1.0;
    if (deadband < 0.0)
        deadband = 0.0;
    if (deadband > 0.99)
        deadband = 0.99;
    if (!(ax > deadband)) {
        out = 0;
        return;
    }
    if (ax >= 1.0) {
        out = in < 0.0 ? -(scale + offset) : scale + offset;
        return;
    }
    // f runs from (deadband, 0) to (1, 1): a*u^power + b*u with a + b = 1
    // (the straight line a*u + b for power 1)
    u = inverse ? 1.0 + deadband - ax : ax;
    if (power == 1.0) {
        double a = 1.0 / (1.0 - deadband);
        f = a * u + (1.0 - a);
    } else {
        double a = 1.0 / (1.0 - pow(deadband, power - 1.0));
        f = a * pow(u, power) + (1.0 - a) * u;
    }
    y = scale * f + offset;
    if (inverse) // 2.9's mirror, including its offset on the negative side
        out = (in < 0.0 ? -(scale + 2.0 * offset) : scale + 2.0 * offset) - y;
    else
        out = in < 0.0 ? 0.0 - y : y;
}
