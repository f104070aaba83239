// SPDX-License-Identifier: GPL-2.0-or-later
// near: are two floats close, by ratio or by absolute difference?
// LinuxCNC 2.9's names and defaults (docs/near.md).
component near "Determine whether two values are roughly equal";
pin in float in1;
pin in float in2;
pin out bit out "TRUE when in1 and in2 are within a factor of scale or within difference";
param rw float scale = 1 "Largest ratio between in1 and in2 that counts as near";
param rw float difference = 0 "Largest absolute difference that counts as near";
function _;
license "GPL";
;;
#include <rtapi_math.h>
FUNCTION(_) {
    double a = in1;
    double b = in2;
    double s = scale;
    int by_ratio = 0;
    /* The ratio test needs scale > 1 (as in LinuxCNC 2.9, so that with
     * scale 1 two infinities are not "near"); it is
     * a/s <= b <= a*s for a > 0 and a*s <= b <= a/s for a < 0. */
    if (s > 1) {
        if (a > 0)
            by_ratio = b >= a / s && b <= a * s;
        else if (a < 0)
            by_ratio = b <= a / s && b >= a * s;
    }
    out = by_ratio || fabs(a - b) <= difference;
}
