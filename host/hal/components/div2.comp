// SPDX-License-Identifier: GPL-2.0-or-later
// div2: quotient of two floats with a deadband around a zero divisor,
// LinuxCNC 2.9's names and behaviour (docs/div2.md): when |in1| is below
// the deadband (at least 1e-12, also when deadband is 0 or negative) the
// divisor is the deadband with the sign of in1 (+ for +-0), and a warning
// is printed once each time the divisor enters the deadband.
component div2 "Quotient of two float inputs";
pin in float in0 "Dividend";
pin in float in1 "Divisor";
pin out float out "in0 / in1";
param rw float deadband "Smallest divisor size used: closer to zero, +-deadband is used";
variable int in_band;
variable char name[48];
function _;
option extra_setup yes;
license "GPL";
;;
#include <rtapi_math.h>
#define DIV2_MIN_DIVISOR 1e-12

EXTRA_SETUP() {
    rtapi_strlcpy(name, prefix, sizeof(name));
    return 0;
}

FUNCTION(_) {
    double d = in1;
    double band = deadband > DIV2_MIN_DIVISOR ? deadband : DIV2_MIN_DIVISOR;
    if (fabs(d) < band) {
        int neg = !(d >= 0);
        if (!in_band) {
            rtapi_print_msg(RTAPI_MSG_WARN,
                            "%s: divisor in1 = %g is within the deadband, %g is used instead: "
                            "increase in1 or lower deadband\n",
                            name, d, neg ? -band : band);
            in_band = 1;
        }
        /* -in0 / band rather than in0 / -band: the same number, and a nan
         * dividend comes out as -nan, as in LinuxCNC 2.9 */
        out = neg ? -in0 / band : in0 / band;
    } else {
        in_band = 0;
        out = in0 / d;
    }
}
