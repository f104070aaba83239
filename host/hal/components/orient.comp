// SPDX-License-Identifier: GPL-2.0-or-later
// orient: the command of a spindle orientation PID loop (M19), LinuxCNC
// 2.9's names and behaviour (docs/orient.md).
component orient "Command input of a spindle orientation PID loop";
pin in bit enable "Orientation mode: the command is set at the rising edge";
pin in s32 mode "0: shorter way, 1: always forward (clockwise), 2: always backward";
pin in float position "Spindle position in revolutions (encoder position)";
pin in float angle "Target angle in degrees";
pin out float command "Target spindle position: input of the PID loop's command";
pin out float poserr "(position - command) in degrees, for PID tuning";
pin out bit is_oriented "TRUE once poserr has been within tolerance for 100 periods";
pin in float tolerance = 0.5 "Tolerance of is-oriented in degrees";
variable int was_enabled;
variable int settled;
function _;
license "GPL";
;;
#include <rtapi_math.h>

/* Periods poserr must spend within tolerance (they need not be
 * consecutive) before is-oriented is set; it then stays set until enable
 * drops. */
#define ORIENT_SETTLE_PERIODS 100

/* The target nearest the position in the mode's direction: whole turns
 * plus the angle's fraction of a turn (fmod: it keeps the angle's sign).
 * The whole turns start at the position's and are moved one at a time
 * (at most twice: the first target is less than two turns off) until the
 * target is where the mode wants it; the fraction is added last.  A NaN
 * or infinite angle or position gives a NaN or infinite target. */
static double orient_target(double pos, double deg, int m, double old)
{
    double frac = fmod(deg / 360.0, 1.0);
    double turns = floor(pos);
    if (m < 0 || m > 2)
        return old; /* an unknown mode leaves the command as it was */
    for (int step = 0; step < 2; step++) {
        double cmd = turns + frac;
        if (m == 0) { /* the shorter way; half a turn back goes forward */
            if (pos - cmd >= 0.5)
                turns += 1.0;
            else if (cmd - pos > 0.5)
                turns -= 1.0;
        } else if (m == 1) { /* at or ahead of the position */
            if (cmd < pos)
                turns += 1.0;
        } else { /* at or behind the position, less than a turn */
            if (cmd > pos)
                turns -= 1.0;
            else if (pos - cmd >= 1.0)
                turns += 1.0;
        }
    }
    return turns + frac;
}

FUNCTION(_) {
    if (!enable) {
        was_enabled = 0;
        settled = 0;
        is_oriented = 0;
        return;
    }
    if (!was_enabled)
        command = orient_target(position, angle, mode, command);
    was_enabled = 1;
    poserr = (position - command) * 360.0;
    if (fabs(poserr) < tolerance) {
        if (settled >= ORIENT_SETTLE_PERIODS)
            is_oriented = 1;
        else
            settled++;
    }
}
