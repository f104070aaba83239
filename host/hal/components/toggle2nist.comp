// SPDX-License-Identifier: GPL-2.0-or-later
// toggle2nist: a momentary push button for a device with separate on and
// off inputs and an is-on feedback, LinuxCNC 2.9's names
// (docs/toggle2nist.md).  Each change of in (press or release, as LinuxCNC
// 2.9 does it) requests the opposite of is-on: `on` while is-on is FALSE,
// `off` while it is TRUE; a request is held until is-on answers.
component toggle2nist "Push button to on/off (NIST style) logic";
pin in bit in "Push button";
pin in bit is_on "Feedback: the device is on";
pin out bit on "Held TRUE after a button change while is-on is FALSE, until is-on";
pin out bit off "Held TRUE after a button change while is-on is TRUE, until it is FALSE";
variable int last_in;
function _ nofp;
license "GPL";
;;
int b = in;
int s = is_on;
if (b != last_in) {
    /* any change of the button asks for the opposite of the present state */
    on = !s;
    off = s;
}
if (on && s)
    on = 0;
if (off && !s)
    off = 0;
last_in = b;
