// SPDX-License-Identifier: GPL-2.0-or-later
// gearchange: speed command limited and scaled for one of two gear ranges,
// LinuxCNC 2.9's names and output (docs/gearchange.md).
component gearchange "Select from one two speed ranges";
pin in bit sel "FALSE: gear 1, TRUE: gear 2";
pin in float speed_in "Commanded speed";
pin out float speed_out "Speed for the drive (DAC/PWM): |speed-in| limited to the gear's range, divided by scale2 in gear 2, sign kept";
pin in bit dir_in "Commanded direction";
pin out bit dir_out "dir-in, inverted in gear 2 when reverse is set";
param rw float min1 = 0 "Lowest speed magnitude in gear 1";
param rw float max1 = 100000 "Highest speed magnitude in gear 1";
param rw float min2 = 0 "Lowest speed magnitude in gear 2";
param rw float max2 = 100000 "Highest speed magnitude in gear 2";
param rw float scale2 = 1.0 "Speed of gear 2 relative to gear 1; set back to 1 when lower";
param rw bit reverse = 0 "TRUE: gear 2 turns the spindle the other way";
function _;
license "GPL";
;;
#include <rtapi_math.h>
FUNCTION(_) {
    double v = fabs(speed_in);
    if (scale2 < 1.0)
        scale2 = 1.0;
    if (!sel) {
        if (v < min1)
            v = min1;
        if (v > max1)
            v = max1;
        dir_out = dir_in;
    } else {
        if (v < min2)
            v = min2;
        if (v > max2)
            v = max2;
        v = v / scale2;
        dir_out = reverse ? !dir_in : dir_in;
    }
    speed_out = speed_in < 0.0 ? -v : v;
}
