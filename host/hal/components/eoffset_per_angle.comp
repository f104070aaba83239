// SPDX-License-Identifier: GPL-2.0-or-later
// eoffset_per_angle: an external offset computed from an angle (a polygon,
// a sinusoid or a square wave), LinuxCNC 2.9's names and behaviour
// (docs/eoffset_per_angle.md).
component eoffset_per_angle "External offset per angle: polygon, sinusoid or square wave";
pin in bit active "Offset still applied: from motion.eoffset-active";
pin in bit is_on "Machine on: from halui.machine.is-on";
pin in bit enable_in "Enables the offset; dropping it returns the offset to zero";
pin in float radius_ref = 1 "Reference radius of the offset";
pin in float angle "Angle in degrees (a rotary coordinate or a spindle angle)";
pin in float start_angle "Angle in degrees where the function starts";
pin in s32 fnum "Function: 0 inside polygon, 1 outside polygon, 2 sinusoid, 3 square wave";
pin in float rfraction = 0.1 "Amplitude as a fraction of radius-ref";
pin in float fmult = 6 "Frequency multiplier (polygon sides for fnum 0 and 1)";
pin in u32 k = 10000 "Counts per unit of kcounts (0: 10000)";
pin out bit is_off "NOT is-on";
pin out bit enable_out "To axis.L.eoffset-enable";
pin out bit clear "To axis.L.eoffset-clear";
pin out s32 kcounts "To axis.L.eoffset-counts: the offset times k";
pin out float kreciprocal "To axis.L.eoffset-scale: 1/k";
pin out float eoffset_dbg "The offset kcounts stands for (kcounts / k)";
pin out u32 state_dbg "State at the start of the period (0 off, 1 ready, 2 running, 3 stopping, 4 stopped)";
variable int state;
variable int failed;
function _;
license "GPL";
;;
#include <rtapi_math.h>

enum { EPA_OFF, EPA_READY, EPA_RUNNING, EPA_STOPPING, EPA_STOPPED };

#define EPA_DEFAULT_K 10000

/* A double to int as x86's conversion does: truncation, and INT_MIN for
 * NaN, infinities and values out of range (no undefined behaviour). */
static int epa_to_int(double x)
{
    if (!(x >= -2147483648.0 && x < 2147483648.0))
        return (int)(-2147483647 - 1);
    return (int)x;
}

/* The number of the polygon side x falls on, truncated toward zero (so
 * negative angles are not folded like positive ones, as in LinuxCNC 2.9);
 * NaN, infinities and numbers out of range give INT64_MIN (x86's
 * conversion, without undefined behaviour). */
static long long epa_side(double x)
{
    if (!(x >= -9223372036854775808.0 && x < 9223372036854775808.0))
        return (long long)(-9223372036854775807LL - 1);
    return (long long)x;
}

/* Distance of a regular polygon of n sides from the reference circle at
 * angle deg (degrees from a side's centre): the polygon's apothem is
 * apo; the angle is first brought into its side's sector.  n infinite
 * gives NaN. */
static double epa_polygon(double r, double apo, double n, double deg)
{
    double sector = 360.0 / n;
    double half = 180.0 / n;
    double x = (deg + half) / sector; /* in sides from the first side's start */
    double phi = ((x - (double)epa_side(x)) * sector - half) * M_PI / 180.0;
    return apo / cos(phi) - r;
}

/* The offset of function fnum at deg degrees from start-angle; *bad is
 * set when a polygon has fewer than three sides (fmult <= 2). */
static double epa_offset(int fn, double r, double rf, double n, double deg, int *bad)
{
    double s;
    *bad = 0;
    if (fn == 2 || fn == 3) {
        s = sin((n * deg - 90.0) * M_PI / 180.0);
        if (fn == 2)
            return r * rf * (1.0 + s) / 2.0;
        return s >= 0.0 ? r * rf : 0.0;
    }
    if (n <= 2.0) {
        *bad = 1;
        return 0.0;
    }
    if (fn == 1)
        return epa_polygon(r, r * (1.0 + rf) * cos(180.0 / n * M_PI / 180.0), n, deg);
    return epa_polygon(r, r * (1.0 + rf), n, deg); /* 0 and unknown values */
}

/* RUNNING: enable-out on and the offset in counts, or the way to
 * STOPPING (enable-in dropped: clear; bad polygon: remembered, so the
 * enable has to be toggled after STOPPED). */
static void epa_run(struct __comp_state *__comp_inst, int kk)
{
    int bad;
    double off;
    if (!enable_in) {
        clear = 1;
        kcounts = 0;
        state = EPA_STOPPING;
        return;
    }
    enable_out = 1;
    off = epa_offset(fnum, radius_ref, rfraction, fmult, angle - start_angle, &bad);
    if (bad) {
        kcounts = 0;
        failed = 1;
        state = EPA_STOPPING;
        return;
    }
    kcounts = epa_to_int(off * kk);
}

FUNCTION(_) {
    int kk = (int)(rtapi_s32)k; /* LinuxCNC reads k as a signed int */
    float kr; /* LinuxCNC 2.9 keeps 1/k in single precision */
    if (kk == 0)
        kk = EPA_DEFAULT_K;
    kr = (float)(1.0 / kk);
    kreciprocal = kr;
    state_dbg = state;
    is_off = !is_on;
    if (!is_on) {
        state = EPA_OFF;
        enable_out = 0;
        kcounts = 0;
    } else {
        switch (state) {
        case EPA_OFF: /* waits for enable-in low */
            if (!enable_in)
                state = EPA_READY;
            break;
        case EPA_READY:
            if (enable_in) {
                failed = 0;
                state = EPA_RUNNING;
            }
            break;
        case EPA_RUNNING:
            epa_run(__comp_inst, kk);
            break;
        case EPA_STOPPING: /* until motion has removed the offset */
            kcounts = 0;
            if (!active)
                state = EPA_STOPPED;
            break;
        default: /* STOPPED */
            enable_out = 0;
            clear = 0;
            kcounts = 0;
            state = failed ? EPA_OFF : EPA_READY;
            break;
        }
    }
    eoffset_dbg = kcounts * (double)kr;
}
