// SPDX-License-Identifier: GPL-2.0-or-later
//
// drive_input.cpp - bridge and step inputs of the drives (drive_input.h).
#include "drive_input.h"

namespace vb::plant {

// ---- H bridge ------------------------------------------------------------------

void BridgeInput::configure(Mode mode, double bus_volts, bool negative_level, bool a0, bool b0,
                            uint64_t t0)
{
    mode_ = mode;
    bus_ = bus_volts;
    negative_ = negative_level;
    a_ = a0;
    b_ = b0;
    v_ = volts(a0, b0);
    integral_ = 0;
    t0_ = last_ = t0;
}

double BridgeInput::volts(bool a, bool b) const
{
    if (mode_ == Mode::UpDown)
        return a == b ? 0.0 : a ? bus_ : -bus_;
    if (!a)
        return 0.0; // off phase: the bridge shorts the motor (recirculation)
    return b == negative_ ? -bus_ : bus_;
}

void BridgeInput::change(bool a, bool b, uint64_t t)
{
    integral_ += v_ * static_cast<double>(t - last_);
    last_ = t;
    a_ = a;
    b_ = b;
    v_ = volts(a, b);
}

double BridgeInput::take_average(uint64_t t)
{
    integral_ += v_ * static_cast<double>(t - last_);
    double span = static_cast<double>(t - t0_);
    double avg = span > 0 ? integral_ / span : v_;
    integral_ = 0;
    t0_ = last_ = t;
    return avg;
}

// ---- step inputs ---------------------------------------------------------------

bool drive_timing(const std::string &model, StepTiming &t)
{
    if (model == "G201")
        t = StepTiming{false, 4000, 500, 1000, 20000};
    else if (model == "G202")
        t = StepTiming{false, 4500, 500, 1000, 20000};
    else if (model == "G203V")
        t = StepTiming{true, 1000, 2000, 200, 200};
    else if (model == "generic")
        t = StepTiming{true, 0, 0, 0, 0};
    else
        return false;
    return true;
}

void StepInput::configure(Mode mode, const StepTiming &timing, bool dir_negative, bool step0,
                          bool dir0, uint64_t t0)
{
    mode_ = mode;
    tm_ = timing;
    dir_negative_ = dir_negative;
    step_ = step0;
    dir_ = dir0;
    step_change_ = dir_change_ = t0;
    old_sign_ = dir0 == dir_negative ? -1 : 1;
}

void StepInput::set_step(bool level, uint64_t t, bool enabled)
{
    if (level == step_)
        return;
    if (mode_ == Mode::Quadrature) {
        quad(level, dir_, t, enabled);
        return;
    }
    uint64_t phase = t - step_change_; // how long the pin was at its old level
    bool ended_high = step_;
    step_ = level;
    step_change_ = t;
    if (level == tm_.rising) {
        // The step edge.  The phase before it must have been long enough for
        // the drive's input to see the pin change at all.
        uint64_t need = ended_high ? tm_.min_high : tm_.min_low;
        int sign = dir_ == dir_negative_ ? -1 : 1;
        c_.edges++;
        c_.commanded += sign;
        if (!enabled) {
            // A disabled drive ignores its inputs (no step, no timing check).
            c_.disabled++;
            pending_ = false;
            have_edge_ = false;
            return;
        }
        if (need && phase < need) {
            (ended_high ? c_.short_high : c_.short_low)++;
            pending_ = false;
            return;
        }
        if (dir_changed_ && tm_.dir_setup && t - dir_change_ < tm_.dir_setup) {
            c_.dir_setup++;
            sign = old_sign_; // the drive still sees the old direction
        }
        pending_ = true;
        pulse_sign_ = sign;
        edge_ = t;
        have_edge_ = true;
        last_counted_ = false;
        return;
    }
    // The phase after the step edge ends: was it long enough?
    if (!pending_)
        return;
    pending_ = false;
    uint64_t need = ended_high ? tm_.min_high : tm_.min_low;
    if (need && phase < need) {
        (ended_high ? c_.short_high : c_.short_low)++;
        return;
    }
    if (!enabled) {
        c_.disabled++;
        return;
    }
    position_ += pulse_sign_;
    c_.accepted++;
    last_counted_ = true;
}

void StepInput::set_dir(bool level, uint64_t t, bool enabled)
{
    if (level == dir_)
        return;
    if (mode_ == Mode::Quadrature) {
        quad(step_, level, t, enabled);
        return;
    }
    old_sign_ = dir_ == dir_negative_ ? -1 : 1;
    dir_ = level;
    dir_change_ = t;
    dir_changed_ = true;
    int sign = level == dir_negative_ ? -1 : 1;
    if (enabled && have_edge_ && tm_.dir_hold && t - edge_ < tm_.dir_hold) {
        // The drive latches the direction late: the last step goes the new way.
        c_.dir_hold++;
        if (pending_) {
            pulse_sign_ = sign;
        } else if (last_counted_ && pulse_sign_ != sign) {
            position_ += 2 * sign;
            pulse_sign_ = sign;
        }
    }
}

void StepInput::quad(bool a, bool b, uint64_t t, bool enabled)
{
    // Gray order 00 -> 10 -> 11 -> 01 is up (A leads B).
    static const int kPhase[4] = {0, 1, 3, 2}; // index b<<1 | a
    int from = kPhase[(dir_ ? 2 : 0) | (step_ ? 1 : 0)];
    int to = kPhase[(b ? 2 : 0) | (a ? 1 : 0)];
    uint64_t state = t - (step_change_ > dir_change_ ? step_change_ : dir_change_);
    if (a != step_)
        step_change_ = t;
    if (b != dir_)
        dir_change_ = t;
    step_ = a;
    dir_ = b;
    int d = (to - from + 4) % 4;
    c_.edges++;
    if (tm_.min_high && state < tm_.min_high)
        c_.short_high++;
    if (d == 2) {
        c_.quad_errors++;
        return;
    }
    int sign = d == 1 ? 1 : -1;
    if (dir_negative_)
        sign = -sign;
    c_.commanded += sign;
    if (!enabled) {
        c_.disabled++;
        return;
    }
    position_ += sign;
    c_.accepted++;
}

} // namespace vb::plant
