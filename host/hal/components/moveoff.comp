// SPDX-License-Identifier: GPL-2.0-or-later
// moveoff: offsets of up to nine joints applied from HAL (offset while a
// program is paused, or always), within position, velocity and
// acceleration limits, returned to zero along the recorded waypoints;
// LinuxCNC 2.9's names, defaults and behaviour (docs/moveoff.md).
component moveoff "Offsets of joint positions made in HAL";
pin in bit power_on "Connect to motion.motion-enabled";
pin in bit move_enable "Enables offsets (together with apply-offsets)";
pin in bit apply_offsets "Enables offsets (together with move-enable)";
pin in bit backtrack_enable = 1 "Return along the recorded waypoints";
pin in float epsilon = 0.0005 "Tolerance of the return to zero (at least 0.0001)";
pin in float waypoint_threshold = 0.02 "Least distance (in one joint) for a new waypoint";
pin in float waypoint_sample_secs = 0.02 "Least time between waypoints, seconds";
pin out bit warning "apply-offsets dropped while offsets were applied";
pin out bit offset_applied "At least one offset is applied";
pin out bit waypoint_limit = 0 "No room for more waypoints: the offsets are frozen";
pin out s32 waypoint_ct "Waypoints recorded";
pin out s32 waypoint_percent_used "Part of the waypoint memory used, percent";
pin in float offset_in_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] "Offset wanted for joint M";
pin in float pos_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] "Joint position (typically joint.M.motor-pos-cmd)";
pin in float fb_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] "Joint feedback";
pin out float offset_current_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] "Offset applied now";
pin out float pos_plusoffset_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] "pos-M plus the offset (to the joint's command)";
pin out float fb_minusoffset_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] "fb-M minus the offset (to joint.M.motor-pos-fb)";
pin in float offset_vel_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] = 10 "Velocity limit of the offset";
pin in float offset_accel_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] = 100 "Acceleration limit of the offset";
pin in float offset_min_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] = -1e20 "Least offset";
pin in float offset_max_#[9 : (personality == 0 ? 3 : personality < 0 ? 0 : personality)] = 1e20 "Greatest offset";
pin in bit dbg_waypoint_limit_test "Debug: room for 50 waypoints only";
pin out s32 dbg_state "State at the start of the period (0 idle, 1 offsetting, 2 returning)";
variable int state;
variable int ct;
variable int target_wp;
variable double elapsed;
variable double thr_l;
variable double wss_l;
variable double eps_l;
variable double *wp;
variable double last_wp[9];
variable double off[9];
variable double fbm[9];
variable double vel[9];
variable double tgt_old[9];
function read_inputs "Read the inputs and compute the offsets";
function write_outputs "Write offset-current-M, pos-plusoffset-M and fb-minusoffset-M";
option extra_setup;
license "GPL";
;;
#include <rtapi_math.h>

#define MO_WAYPOINTS 1000
#define MO_TEST_WAYPOINTS 50
#define MO_EPS_MIN 0.0001

enum { MO_IDLE, MO_AWAY, MO_RETURN };

static int mo_joints(int pers)
{
    return pers == 0 ? 3 : pers < 0 ? 0 : pers;
}

EXTRA_SETUP()
{
    int n = mo_joints(personality);
    if (n > 0) {
        wp = hal_malloc((long)MO_WAYPOINTS * n * (long)sizeof(double));
        if (!wp) {
            rtapi_print_msg(RTAPI_MSG_ERR, "moveoff: %s: no memory for %d waypoints\n", prefix,
                            MO_WAYPOINTS);
            return -ENOMEM;
        }
    }
    return 0;
}

FUNCTION(write_outputs)
{
    int j, n = mo_joints(personality);
    for (j = 0; j < n; j++) {
        offset_current(j) = off[j];
        pos_plusoffset(j) = pos(j) + off[j];
        fb_minusoffset(j) = fbm[j];
    }
}

/* One period of joint j's planner toward tgt; returns the new offset.
 * The target is first clamped to offset-min .. offset-max.  The offset's
 * velocity changes by at most accel x period and stays within +-vel.
 * When the target, and its own velocity, are within reach this period,
 * the offset lands on it.  Otherwise the offset ramps toward the target's
 * velocity, unless the estimated gap left once the two velocities match
 * shrinks by ramping the other way this period. */
static double mo_step(struct __comp_state *__comp_inst, int j, double tgt, double T)
{
    double p = off[j], v = vel[j];
    double amax = offset_accel(j), vmax = offset_vel(j);
    double tv, lo_v, hi_v, lo_p, hi_p, a, t_match, gap, flip;
    if (tgt < offset_min(j))
        tgt = offset_min(j);
    if (tgt > offset_max(j))
        tgt = offset_max(j);
    tv = (tgt - tgt_old[j]) / T;
    tgt_old[j] = tgt;
    lo_v = v - amax * T;
    if (lo_v < -vmax)
        lo_v = -vmax;
    hi_v = v + amax * T;
    if (hi_v > vmax)
        hi_v = vmax;
    lo_p = p + lo_v * T;
    hi_p = p + hi_v * T;
    if (tgt >= lo_p && tgt <= hi_p && tv >= lo_v && tv <= hi_v) {
        vel[j] = (tgt - p) / T;
        return tgt;
    }
    a = tv > v ? amax : -amax;
    t_match = (tv - v) / a;
    /* offset minus target when the velocities match */
    gap = (p + (tv + v) * 0.5 * (t_match + T)) - (tgt + tv * t_match);
    /* how that changes with one period of the other ramp */
    flip = -2.0 * a * T * t_match;
    if (fabs(gap + flip) < fabs(gap))
        a = -a;
    vel[j] = a < 0.0 ? lo_v : hi_v;
    return a < 0.0 ? lo_p : hi_p;
}

/* The waypoint the return heads for: index k of the recorded ones, or
 * zero (home) for k < 0. */
static double mo_wp(struct __comp_state *__comp_inst, int n, int k, int j)
{
    return k < 0 ? 0.0 : wp[k * n + j];
}

static int mo_reached(struct __comp_state *__comp_inst, int n, int k, double eps)
{
    int j;
    for (j = 0; j < n; j++)
        if (!(fabs(off[j] - mo_wp(__comp_inst, n, k, j)) < eps))
            return 0;
    return 1;
}

static void mo_record(struct __comp_state *__comp_inst, int n, double T)
{
    int j, far = 0;
    elapsed += T;
    if (elapsed < wss_l)
        return;
    for (j = 0; j < n; j++)
        if (fabs(off[j] - last_wp[j]) > thr_l)
            far = 1;
    if (!far)
        return;
    for (j = 0; j < n; j++) {
        wp[ct * n + j] = off[j];
        last_wp[j] = off[j];
    }
    ct++;
    elapsed = 0;
}

static void mo_feedback(struct __comp_state *__comp_inst, int n)
{
    int j;
    for (j = 0; j < n; j++)
        fbm[j] = fb(j) - off[j];
}

/* Back home: the offsets become exactly zero, at rest. */
static void mo_home(struct __comp_state *__comp_inst, int n)
{
    int j;
    for (j = 0; j < n; j++) {
        off[j] = 0;
        vel[j] = 0;
        tgt_old[j] = 0;
    }
    state = MO_IDLE;
    warning = 0;
    ct = 0;
}

/* Offsetting: record a waypoint when due, then follow offset-in, unless
 * the waypoint memory is full (the offsets and fb-minusoffset freeze). */
static void mo_away(struct __comp_state *__comp_inst, int n, int limit, double T)
{
    int j;
    if (ct < limit)
        mo_record(__comp_inst, n, T);
    waypoint_limit = ct >= limit;
    if (waypoint_limit)
        return;
    mo_feedback(__comp_inst, n);
    for (j = 0; j < n; j++)
        off[j] = mo_step(__comp_inst, j, offset_in(j), T);
}

/* From offsetting to returning: toward the last waypoint (backtracking)
 * or straight home. */
static void mo_start_return(struct __comp_state *__comp_inst)
{
    waypoint_limit = 0;
    state = MO_RETURN;
    if (backtrack_enable && ct > 0) {
        ct--;
        target_wp = ct;
    } else {
        target_wp = -1;
    }
}

/* Returning: a waypoint reached (all joints within eps) counts ct down;
 * the next target is waypoint ct + 1 (so the first one counts twice, as
 * in LinuxCNC 2.9), home once ct is 0.  The period that starts the return
 * (check 0) heads for waypoint ct without looking whether it is there. */
static void mo_return(struct __comp_state *__comp_inst, int n, double eps, int check, double T)
{
    int j;
    if (check && ct == 0) {
        target_wp = -1;
    } else if (check && target_wp >= 0 && mo_reached(__comp_inst, n, target_wp, eps)) {
        ct--;
        target_wp = ct > 0 ? ct + 1 : -1;
    }
    mo_feedback(__comp_inst, n);
    for (j = 0; j < n; j++)
        off[j] = mo_step(__comp_inst, j, mo_wp(__comp_inst, n, target_wp, j), T);
}

FUNCTION(read_inputs)
{
    int j, n = mo_joints(personality);
    int limit = dbg_waypoint_limit_test ? MO_TEST_WAYPOINTS : MO_WAYPOINTS;
    int enabled = apply_offsets && move_enable;
    int applied = 0;
    dbg_state = state;
    if (state == MO_IDLE) {
        /* these three are taken only while idle */
        eps_l = epsilon < MO_EPS_MIN ? MO_EPS_MIN : epsilon;
        thr_l = waypoint_threshold;
        wss_l = waypoint_sample_secs;
    }
    if (!power_on) {
        /* motion disabled: the offsets are gone at once */
        mo_home(__comp_inst, n);
        waypoint_limit = 0;
        mo_feedback(__comp_inst, n);
        goto outputs;
    }
    if (apply_offsets)
        warning = 0;
    else if (offset_applied)
        warning = 1;
    switch (state) {
    case MO_IDLE:
        mo_feedback(__comp_inst, n);
        if (!enabled || !power_on)
            break;
        state = MO_AWAY;
        ct = 0;
        elapsed = 0;
        for (j = 0; j < n; j++)
            last_wp[j] = 0;
        mo_away(__comp_inst, n, limit, fperiod);
        break;
    case MO_AWAY:
        if (enabled) {
            mo_away(__comp_inst, n, limit, fperiod);
            break;
        }
        mo_start_return(__comp_inst);
        mo_return(__comp_inst, n, eps_l, 0, fperiod);
        break;
    case MO_RETURN:
        if (target_wp < 0 && mo_reached(__comp_inst, n, -1, eps_l)) {
            mo_home(__comp_inst, n);
            mo_feedback(__comp_inst, n);
            break;
        }
        mo_return(__comp_inst, n, eps_l, 1, fperiod);
        break;
    }
outputs:
    for (j = 0; j < n; j++)
        if (fabs(off[j]) > eps_l)
            applied = 1;
    offset_applied = applied;
    if (state == MO_RETURN && !applied)
        ct = 0;
    waypoint_ct = ct;
    waypoint_percent_used = 100 * ct / limit;
}
