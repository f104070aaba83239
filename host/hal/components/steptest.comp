// SPDX-License-Identifier: GPL-2.0-or-later
//
// steptest: the axis exerciser Stepconf uses to try acceleration and
// velocity settings, LinuxCNC 2.9's steptest (docs/steptest.md).  It only
// sets position-cmd; the step generator behind it (stepgen in position
// mode, with the maxvel and maxaccel being tried) makes the move, and
// position-fb tells steptest when it has arrived.
component steptest "Used by Stepconf to allow testing of acceleration and velocity values for an axis";
pin in bit jog_minus "Drive TRUE to jog the axis in its minus direction";
pin in bit jog_plus "Drive TRUE to jog the axis in its positive direction";
pin in bit run "Drive TRUE to run the axis near its current position-fb, back and forth";
pin in float maxvel "Maximum velocity (sets the jog step)";
pin in float maxaccel "Permitted acceleration (not used by steptest itself, as in 2.9)";
pin in float amplitude "Approximate amplitude of positions to command during run";
pin in s32 dir "Direction from the start to test: 0 both, 1 positive, 2 negative";
pin out float position_cmd;
pin in float position_fb;
pin out bit running;
pin out float run_target "Never written (0), as in LinuxCNC 2.9";
pin out float run_start;
pin out float run_low;
pin out float run_high;
pin in s32 pause = 0 "Pause time at each end of the run, in seconds";
param rw float epsilon = .001 "How close position-fb must be to a target";
param r float elapsed "Time spent at the current end of the run (s)";
variable int state;
variable int stopping;
variable int to_high;
function _;
license "GPL";
;;
/* state while running */
#define ST_MOVING 0
#define ST_PAUSE 1

/* One period (docs/steptest.md):
 *  idle: jog-minus (first) or jog-plus command position-fb -/+ 2 maxvel
 *        periods ahead; otherwise position-cmd follows position-fb when
 *        they differ by more than 1e-5.
 *  run:  start at position-fb, low and high ends by dir and amplitude;
 *        command the low end, then at each end (position-fb within
 *        epsilon) wait pause seconds and with position-fb still there
 *        command the other end.
 *  run released: command the start; stop once position-fb is there with
 *        run still released. */
double fb = position_fb;
if (!running && run) {
    running = 1;
    stopping = 0;
    state = ST_MOVING;
    to_high = 0;
    run_start = fb;
    run_low = dir == 1 ? fb : fb - amplitude;
    run_high = dir == 2 ? fb : fb + amplitude;
}
if (running) {
    if (!run)
        stopping = 1;
    if (state == ST_PAUSE)
        elapsed += fperiod;
    if (stopping) {
        position_cmd = run_start;
        if (!run && fabs(fb - run_start) < epsilon)
            running = 0;
    } else {
        double target = to_high ? run_high : run_low;
        if (state == ST_MOVING) {
            position_cmd = target;
            if (fabs(fb - target) < epsilon) {
                state = ST_PAUSE;
                elapsed = 0;
            }
        } else if (fabs(fb - target) < epsilon && elapsed >= pause) {
            to_high = !to_high;
            position_cmd = to_high ? run_high : run_low;
            state = ST_MOVING;
        }
    }
} else if (jog_minus) {
    position_cmd = fb - 2 * maxvel * fperiod;
} else if (jog_plus) {
    position_cmd = fb + 2 * maxvel * fperiod;
} else if (fabs(fb - position_cmd) > 1e-5) {
    position_cmd = fb;
}
