// SPDX-License-Identifier: GPL-2.0-or-later
// mux16: one of sixteen float inputs, chosen by four select bits in binary
// or Gray code, with optional debounce and suppression of the all-FALSE
// selection; LinuxCNC 2.9's names and behaviour (docs/mux16.md).
component mux16 "Select one of sixteen float inputs";
pin in bit use_graycode "The select bits are Gray code (one bit changes per step)";
pin in bit suppress_no_input "All select bits FALSE keeps the output (in00 is then unused)";
pin in float debounce_time "A new selection is used once it has differed this long (s)";
pin in bit sel#[4] "Select bit # (weight 2^#)";
pin out float out_f "The selected input";
pin out s32 out_s "The selected input, truncated (-2147483648 when out of range)";
pin in float in##[16] "Input MM";
param r float elapsed "Time the selection has differed from the one in use (debounce)";
param r s32 selected "The input in use";
function _;
license "GPL";
;;
FUNCTION(_) {
    int b = (sel(0) ? 1 : 0) | (sel(1) ? 2 : 0) | (sel(2) ? 4 : 0) | (sel(3) ? 8 : 0);
    if (use_graycode) {
        /* Gray to binary: each bit is the XOR of itself and the bits above */
        b ^= b >> 1;
        b ^= b >> 2;
    }
    if (suppress_no_input && b == 0)
        return;
    /* Debounce as LinuxCNC 2.9 does it: the timer runs while the selection
     * differs from the one in use and is cleared only when a new selection
     * is taken; a selection that returns to the one in use just stops it.
     * While a new selection waits, the outputs are left alone. */
    if (b != selected) {
        if (elapsed >= debounce_time) {
            selected = b;
            elapsed = 0;
        } else {
            elapsed = elapsed + fperiod;
            return;
        }
    }
    double v = in(selected & 15);
    out_f = v;
    /* truncation; out of the s32 range (or nan) gives -2147483648, as the
     * conversion does on the machines LinuxCNC 2.9 runs on */
    out_s = (v > -2147483649.0 && v < 2147483648.0) ? (hal_s32_t)v : INT32_MIN;
}
