// SPDX-License-Identifier: GPL-2.0-or-later
//
// limit3's planner (docs/limit3.md): each period the output moves towards
// the target (the input clamped to min..max, or 0 when disabled) with
// |velocity| <= maxv and |velocity change| <= maxa x period.  The target is
// treated as moving at the input's last velocity, so the planning happens
// in the frame of the input: the gap and the closing speed are relative to
// it.  Per period, in this order:
//   1. hold: at the target and at rest, stay.
//   2. snap: when the gap closes within one period at the present closing
//      speed (2 x gap / speed <= one period, or the speed is ~0) and the
//      jump to the target is within maxa and maxv, the output is the target.
//   3. accelerate towards the target by maxa (velocity capped at maxv) if,
//      from there, braking at maxa still stops short of the target (the
//      discrete stopping distance w|w|/2a - wT/2 of the relative speed w,
//      with a 1e-9 tolerance); below min (above max), while stopping would
//      leave the output there, the limit is the point not to pass instead,
//      and the input counts as standing still.
//   4. smooth: with smooth-steps >= 2, if the gap closes in fewer than
//      smooth-steps periods, spread the braking over ceil(that) periods,
//      when that needs no more than maxa.
//   5. otherwise brake by maxa (velocity capped at -maxv).
// Velocity is (out - previous out) / period.  These rules and their
// floating-point order reproduce LinuxCNC 2.9's output bit for bit on the
// recorded cases in tests/hal/limit3-* (docs/limit3.md lists the corners
// where they are known not to).
#ifndef HM_LIMIT3_MATH_H
#define HM_LIMIT3_MATH_H

#include <limits.h>
#include <math.h>

typedef struct {
    double out;    // output position
    double vel;    // (out - previous out) / period
    double in_old; // previous (enabled) input
} limit3_state_t;

typedef struct {
    double cmd, lo, hi, vmax, amax; // in, min, max, maxv, maxa
    int enabled, loading;           // enable, load
    unsigned smooth;                // smooth-steps
} limit3_input_t;

#define LIMIT3_EPS 1e-9      // position tolerance of the braking test
#define LIMIT3_VEPS 1e-9     // closing speed below which it counts as 0
#define LIMIT3_STEP_EPS 1e-6 // slack when rounding periods up

// The integer conversion of the x86 cvttsd2si instruction: values out of
// int range and NaN give INT_MIN (C leaves this undefined; spelled out).
static inline int limit3_to_int(double x)
{
    if (!(x > (double)INT_MIN - 1.0 && x < (double)INT_MAX + 1.0))
        return INT_MIN;
    return (int)x;
}

// Discrete stopping distance from relative speed w braking at a per period.
static inline double limit3_stop_dist(double w, double a, double T)
{
    return w * fabs(w) / (2.0 * a) - w * T / 2.0;
}

static inline double limit3_clamp_target(const limit3_input_t *x, double raw)
{
    double tgt = raw;
    if (tgt < x->lo)
        tgt = x->lo;
    if (tgt > x->hi)
        tgt = x->hi;
    return tgt;
}

// The next output, from position p and velocity v (see the rules above).
static inline double limit3_plan(const limit3_input_t *x, double p, double v,
                                 double tgt, double in_v, double T)
{
    double dv = x->amax * T;
    double rem = tgt - p;
    double remr = tgt - p - in_v * T;
    double vr = v - in_v;
    if (rem == 0.0 && v == 0.0)
        return p;
    double d = remr > 0.0 ? 1.0 : -1.0;
    if (remr == 0.0)
        d = vr >= 0.0 ? 1.0 : -1.0;
    double r = d * remr, u = d * vr;
    int tiny = fabs(u) < LIMIT3_VEPS;
    double ta = tiny ? INFINITY : 2.0 * r / (fabs(u) * T);
    double t = tiny ? INFINITY : 2.0 * r / (u * T);
    int n = limit3_to_int(ceil(t - LIMIT3_STEP_EPS));
    double vt = rem / T;
    if (isnan(ta)) // NaN or infinite input: keep the velocity
        return p + v * T;
    if ((tiny || ta <= 1.0) && fabs(vt - v) <= dv && fabs(vt) <= x->vmax)
        return tgt;
    double ua = fmin(d * v + dv, x->vmax);
    double pn = p + d * ua * T;
    // outside min..max and stopping now would stay outside: the limit is
    // the point not to pass
    double vstop = limit3_stop_dist(v * d, x->amax, T);
    int ok;
    if (d > 0.0 && pn < x->lo && p + vstop < x->lo)
        ok = d * pn + limit3_stop_dist(ua, x->amax, T) <= d * x->lo + LIMIT3_EPS;
    else if (d < 0.0 && pn > x->hi && p - vstop > x->hi)
        ok = d * pn + limit3_stop_dist(ua, x->amax, T) <= d * x->hi + LIMIT3_EPS;
    else
        ok = d * p + ua * T + limit3_stop_dist(ua - d * in_v, x->amax, T) <=
             d * tgt + LIMIT3_EPS;
    if (ok)
        return pn;
    if (x->smooth >= 2 && n != 0 && ta < (double)x->smooth &&
        fabs(u / n) <= dv) {
        double acc = -u / (n * T);
        return p + (v + d * acc * T) * T;
    }
    double ud = fmax(d * v - dv, -x->vmax);
    return p + d * ud * T;
}

// One period of length T seconds; returns the new output.
static inline double limit3_step(limit3_state_t *s, const limit3_input_t *x, double T)
{
    double raw = x->enabled ? x->cmd : 0.0;
    double tgt = limit3_clamp_target(x, raw);
    double in_v = (raw - s->in_old) / T;
    double p = s->out;
    s->in_old = raw;
    double next;
    if (x->loading) {
        next = tgt;
    } else {
        if ((p < x->lo && tgt >= x->lo) || (p > x->hi && tgt <= x->hi))
            in_v = 0.0;
        next = limit3_plan(x, p, s->vel, tgt, in_v, T);
    }
    s->vel = (next - p) / T;
    s->out = next;
    return next;
}

#endif
