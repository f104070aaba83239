// SPDX-License-Identifier: GPL-2.0-or-later
// abs: absolute value and sign of a float, LinuxCNC 2.9's names and
// behaviour (docs/abs.md).
component abs "Compute the absolute value and sign of the input signal";
pin in float in "Analog input value";
pin out float out "Analog output value, always positive";
pin out bit sign "Sign of input, false for positive, true for negative";
pin out bit is_positive "TRUE if input is positive, FALSE if input is 0 or negative";
pin out bit is_negative "TRUE if input is negative, FALSE if input is 0 or positive";
function _;
license "GPL";
;;
#include <rtapi_math.h>
/* 2.9 reports a sign only beyond +-1e-6 (checked on it: 1e-6 -> FALSE,
 * 1.1e-6 -> TRUE), a deadband its man page does not mention */
#define ABS_DEADBAND 0.000001

FUNCTION(_) {
    double v = in;
    if (v >= 0.0) {
        sign = 0;
        out = fabs(v);
    } else {
        sign = 1;
        out = -v;
    }
    is_positive = v > ABS_DEADBAND;
    is_negative = v < -ABS_DEADBAND;
}
