// SPDX-License-Identifier: GPL-2.0-or-later
// toggle: push-on, push-off from a momentary push button, LinuxCNC 2.9's
// names and default (docs/toggle.md).
//
// The button is debounced by an integrator: a count goes up (to debounce)
// each period the button reads TRUE and down (to 0) each period it reads
// FALSE.  The button counts as pressed when the count reaches debounce and
// as released when it is back at 0; each press toggles out.  debounce 1
// therefore toggles on every rising edge, debounce N needs N periods of
// press and N periods of release.  debounce 0 acts as 2, as in LinuxCNC 2.9.
component toggle "Push-on, push-off from a momentary push button";
pin in bit in "Push button";
pin io bit out "Toggled by each debounced press";
param rw u32 debounce = 2 "Periods of press (and of release) a button change needs";
variable unsigned count;
variable int pressed;
function _ nofp;
license "GPL";
;;
unsigned limit = debounce ? debounce : 2u;
if (count > limit)
    count = limit;
if (in) {
    if (count < limit)
        count++;
} else if (count > 0) {
    count--;
}
if (count >= limit && !pressed) {
    pressed = 1;
    out = !out;
} else if (count == 0 && pressed) {
    pressed = 0;
}
