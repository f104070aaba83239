// SPDX-License-Identifier: GPL-2.0-or-later
// The motion controller's stand-in functions for `make compat` (docs/compat.md).
// Loaded as `loadrt compat_motion names=motion-command-handler,motion-controller`:
// each instance exports one function named after it, doing nothing, so the
// configurations' `addf motion-command-handler servo-thread` lines place it
// and `show thread` lists it where LinuxCNC lists motion's functions.
component compat_motion "no-op stand-in for the motion controller's functions (make compat only)";
pin out bit placed "always 0: the instance only provides its function";
function _ nofp "does nothing";
license "GPL";
;;
FUNCTION(_) { placed = 0; }
