// SPDX-License-Identifier: GPL-2.0-or-later
// oneshot: a pulse of `width` seconds on the chosen edges of in, LinuxCNC
// 2.9's names and defaults (docs/oneshot.md).
component oneshot "One-shot pulse generator";
pin in bit in "Trigger";
pin in bit reset "TRUE ends the pulse and ignores triggers";
pin out bit out "TRUE during the pulse";
pin out bit out_not "FALSE during the pulse";
pin in float width = 0 "Pulse width in seconds";
pin out float time_left "Time left in the current pulse, in seconds";
param rw bit retriggerable = TRUE "A trigger during a pulse starts it again";
param rw bit rising = TRUE "Trigger on rising edges";
param rw bit falling = FALSE "Trigger on falling edges";
variable int last_in;
variable double timer;
function _ "Produce output pulses from input edges";
license "GPL";
;;
if (reset) {
    /* out goes low at once and the pulse is over (the time-left pin keeps
     * showing where it was until the next run without reset); an input
     * still high after the reset counts as a new rising edge */
    timer = 0;
    out = 0;
    out_not = 1;
    last_in = 0;
    return;
}
int now = in;
int trig = (rising && now && !last_in) || (falling && !now && last_in);
last_in = now;
if (trig && (retriggerable || timer <= 0)) {
    timer = width;
} else if (timer > 0) {
    double t = timer - fperiod;
    timer = t > 0 ? t : 0;
}
time_left = timer;
out = timer > 0;
out_not = !out;
