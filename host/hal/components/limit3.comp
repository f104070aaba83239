// SPDX-License-Identifier: GPL-2.0-or-later
// limit3: follow the input within position, velocity and acceleration
// limits, LinuxCNC 2.9's names and output (docs/limit3.md).  The planner is
// math/limit3_math.h.
component limit3 "Follow input signal while obeying limits";
pin in float in;
pin in bit enable = 1 "TRUE: out follows in; FALSE: out goes to 0, within the limits";
pin out float out;
pin in bit load = 0 "TRUE: out is in (clamped to min..max) at once, without maxv and maxa";
pin in float min_ = -1e20;
pin in float max_ = 1e20;
pin in float maxv = 1e20;
pin in float maxa = 1e20;
pin in u32 smooth_steps = 2 "Braking is spread over up to this many periods before the target is reached (0 or 1: bang-bang)";
variable limit3_state_t st;
function _ "Update out from in and the limits";
include "math/limit3_math.h";
description """
out follows in, kept within min..max, with a rate of change of at most maxv
per second and a second derivative of at most maxa per second squared: for a
position, a time-optimal move within position, velocity and acceleration
limits.
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
