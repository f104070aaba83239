// SPDX-License-Identifier: GPL-2.0-or-later
// biquad: second-order IIR filter, LinuxCNC 2.9's names and output
// (docs/biquad.md).
component biquad "Biquad IIR filter";
pin in float in "Filter input";
pin out float out "Filter output (in while disabled or invalid)";
pin in bit enable = 0 "TRUE: filter; a rising edge computes the coefficients for type, f0 and Q";
pin out bit valid = 0 "FALSE when the last rising edge found type, f0 or Q unusable";
pin in u32 type = 0 "0: the coefficients in n0..d2 as set; 1: low pass; 2: notch";
pin in float f0 = 250.0 "Corner (type 1) or centre (type 2) frequency, Hz";
pin in float Q = 0.7071 "Quality factor, 0.5..2";
pin out float s1 = 0.0 "First delayed state (for inspection)";
pin out float s2 = 0.0 "Second delayed state (for inspection)";
param rw float d1 = 0.0 "Denominator coefficient of z^-1";
param rw float d2 = 0.0 "Denominator coefficient of z^-2";
param rw float n0 = 1.0 "Numerator coefficient of z^0";
param rw float n1 = 0.0 "Numerator coefficient of z^-1";
param rw float n2 = 0.0 "Numerator coefficient of z^-2";
variable int was_enabled;
function _;
license "GPL";
;;
#include <rtapi_math.h>

// pi as 2.9 writes it (to 12 decimals): its coefficients, bit for bit
#define BIQUAD_PI 3.141592653589

// Robert Bristow-Johnson's low-pass and notch designs, normalized by a0.
// Returns 0 when type, f0 (above half the sample rate) or Q (outside
// 0.5..2) cannot be used; NaN slips through, as in 2.9.
static int biquad_design(struct __comp_state *__comp_inst, double fs)
{
    double w0, c, alpha, a0;
    if (type == 0)
        return 1;
    if (type != 1 && type != 2)
        return 0;
    if (Q < 0.5 || Q > 2.0 || f0 > fs / 2.0)
        return 0;
    w0 = 2.0 * BIQUAD_PI * f0 / fs;
    c = cos(w0);
    alpha = sin(w0) / (2.0 * Q);
    a0 = 1.0 + alpha;
    if (type == 1) {
        n0 = (1.0 - c) / 2.0 / a0;
        n1 = (1.0 - c) / a0;
        n2 = (1.0 - c) / 2.0 / a0;
    } else {
        n0 = 1.0 / a0;
        n1 = -2.0 * c / a0;
        n2 = 1.0 / a0;
    }
    d1 = -2.0 * c / a0;
    d2 = (1.0 - alpha) / a0;
    s1 = 0.0;
    s2 = 0.0;
    return 1;
}

FUNCTION(_) {
    double x = in, y;
    if (enable && !was_enabled)
        valid = biquad_design(__comp_inst, 1.0 / fperiod);
    was_enabled = enable;
    if (!enable || !valid) {
        out = x;
        return;
    }
    // transposed direct form II
    y = n0 * x + s1;
    s1 = n1 * x - d1 * y + s2;
    s2 = n2 * x - d2 * y;
    out = y;
}
