// SPDX-License-Identifier: GPL-2.0-or-later
// timedelay: a time-delay relay, LinuxCNC 2.9's names and defaults
// (docs/timedelay.md).
component timedelay "The equivalent of a time-delay relay";
pin in bit in;
pin out bit out "Follows in once in has held its new value for the delay";
pin in float on_delay = 0.5 "Seconds in must be TRUE before out becomes TRUE";
pin in float off_delay = 0.5 "Seconds in must be FALSE before out becomes FALSE";
pin out float elapsed "Time in has differed from out (kept after out follows)";
variable int timing;
function _;
license "GPL";
;;
int v = in;
if (v == out) {
    /* settled: elapsed keeps showing how long the last change took */
    timing = 0;
} else {
    if (!timing) {
        elapsed = 0;
        timing = 1;
    }
    elapsed = elapsed + fperiod;
    if (elapsed >= (v ? on_delay : off_delay)) {
        out = v;
        timing = 0;
    }
}
