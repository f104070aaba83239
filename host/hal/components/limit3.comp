// SPDX-License-Identifier: GPL-2.0-or-later
// limit3: follow the input within position, velocity and acceleration
// limits, LinuxCNC 2.9's names and output (docs/limit3.md).  The planner is
// math/limit3_math.h.
component limit3 "Follow input signal while obeying limits";
pin in float in;
pin in bit enable = 1 "1: out follows in, 0: out returns to 0 (always per constraints)";
pin out float out;
pin in bit load = 0 "When TRUE, immediately set out to in, ignoring maxv and maxa";
pin in float min_ = -1e20;
pin in float max_ = 1e20;
pin in float maxv = 1e20;
pin in float maxa = 1e20;
pin in u32 smooth_steps = 2 "Smooth out acceleration this many periods before reaching input or max/min limit. Higher values avoid oscillation, but will accelerate slightly more slowly.";
variable limit3_state_t st;
function _ "Update out from in and the limits";
include "math/limit3_math.h";
description """
Limit the output signal to fall between min and max, limit its slew rate
to less than maxv per second, and limit its second derivative to less
than maxa per second squared.  When the signal is a position, this means
that the position, velocity, and acceleration are limited.
""";
license "GPL";
;;
limit3_input_t x;
x.cmd = in;
x.lo = min_;
x.hi = max_;
x.vmax = maxv;
x.amax = maxa;
x.enabled = enable;
x.loading = load;
x.smooth = smooth_steps;
out = limit3_step(&st, &x, fperiod);
