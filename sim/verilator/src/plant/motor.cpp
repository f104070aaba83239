// SPDX-License-Identifier: GPL-2.0-or-later
//
// motor.cpp - DC brush motor and stepper motor models (motor.h).
#include "motor.h"

#include <cmath>

namespace vb::plant {

double friction_torque(const Shaft &s, const ShaftState &st, double drive)
{
    if (s.coulomb <= 0)
        return 0;
    if (!st.stuck && st.speed != 0)
        return -std::copysign(s.coulomb, st.speed);
    // At rest: static friction balances a drive torque below breakaway.
    if (std::fabs(drive) <= s.coulomb)
        return -drive;
    return -std::copysign(s.coulomb, drive);
}

namespace {

// A shaft at rest, or whose speed went through zero in the step, sticks
// when the torque driving it cannot overcome the friction.  Without
// Coulomb friction nothing ever sticks (the linear model is then exact).
void settle(const Shaft &s, ShaftState &st, const ShaftState &before, double drive)
{
    if (s.coulomb <= 0) {
        st.stuck = false;
        return;
    }
    bool through_zero = before.stuck || before.speed == 0 ||
                        (before.speed > 0) != (st.speed > 0);
    if (through_zero && std::fabs(drive) <= s.coulomb) {
        if (before.stuck)
            st.angle = before.angle;
        st.speed = 0;
        st.stuck = true;
    } else {
        st.stuck = false;
    }
}

// Mechanical part alone: x = [w, theta], u = [torque].
void set_mech(Zoh<2, 1> &z, double inertia, double viscous, double h)
{
    Eigen::Matrix2d a;
    a << -viscous / inertia, 0, 1, 0;
    Eigen::Matrix<double, 2, 1> b;
    b << 1 / inertia, 0;
    z.set(a, b, h);
}

} // namespace

// ---- DC motor ----------------------------------------------------------------

void DcMotor::configure(const DcMotorParams &p, double h)
{
    p_ = p;
    const Shaft &s = p.shaft;
    Eigen::Matrix3d a;
    a << -p.resistance / p.inductance, -p.ke / p.inductance, 0, //
        p.kt / s.inertia, -s.viscous / s.inertia, 0,            //
        0, 1, 0;
    Eigen::Matrix<double, 3, 2> b;
    b << 1 / p.inductance, 0, //
        0, 1 / s.inertia,     //
        0, 0;
    drive_.set(a, b, h);
    set_mech(coast_, s.inertia, s.viscous, h);
}

void DcMotor::step(double v, bool enabled)
{
    const Shaft &s = p_.shaft;
    ShaftState before = st_;
    if (!enabled) {
        // Open bridge: the current dies at once (the inductor's energy goes
        // back to the supply through the diodes), the shaft coasts.
        current_ = 0;
        double drive = s.load;
        double tau = drive + friction_torque(s, st_, drive);
        Eigen::Vector2d x(st_.speed, st_.angle);
        x = coast_.step(x, Eigen::Matrix<double, 1, 1>(tau));
        st_.speed = x[0];
        st_.angle = x[1];
        settle(s, st_, before, drive);
        return;
    }
    if (v > p_.voltage_limit)
        v = p_.voltage_limit;
    else if (v < -p_.voltage_limit)
        v = -p_.voltage_limit;
    double drive = p_.kt * current_ + s.load;
    double ext = s.load + friction_torque(s, st_, drive);
    Eigen::Vector3d x(current_, st_.speed, st_.angle);
    x = drive_.step(x, Eigen::Vector2d(v, ext));
    current_ = x[0];
    st_.speed = x[1];
    st_.angle = x[2];
    // The amplifier regulates the current down to its limit.
    if (current_ > p_.current_limit || current_ < -p_.current_limit) {
        current_ = std::copysign(p_.current_limit, current_);
        limited_++;
    }
    settle(s, st_, before, p_.kt * current_ + s.load);
}

// ---- stepper motor -------------------------------------------------------------

void StepperMotor::configure(const StepperParams &p, double h)
{
    p_ = p;
    set_mech(mech_, p.shaft.inertia, p.shaft.viscous + p.damping, h);
    set_mech(free_, p.shaft.inertia, p.shaft.viscous, h);
}

double StepperMotor::pullout(double speed) const
{
    const auto &c = p_.curve;
    speed = std::fabs(speed);
    if (c.empty())
        return 0;
    if (speed <= c.front().first)
        return c.front().second;
    for (size_t k = 1; k < c.size(); k++)
        if (speed <= c[k].first) {
            double f = (speed - c[k - 1].first) / (c[k].first - c[k - 1].first);
            return c[k - 1].second + f * (c[k].second - c[k - 1].second);
        }
    return c.back().second;
}

void StepperMotor::rebase(double phi)
{
    double lag = phi - teeth() * st_.angle;
    period_ = static_cast<int64_t>(std::floor((lag + M_PI) / (2 * M_PI)));
}

void StepperMotor::step(double phi, bool powered)
{
    const Shaft &s = p_.shaft;
    ShaftState before = st_;
    double lag = phi - teeth() * st_.angle;
    double motor = powered ? pullout(st_.speed) * std::sin(lag) : 0.0;
    double drive = motor + s.load;
    double tau = drive + friction_torque(s, st_, drive);
    Eigen::Vector2d x(st_.speed, st_.angle);
    x = (powered ? mech_ : free_).step(x, Eigen::Matrix<double, 1, 1>(tau));
    st_.speed = x[0];
    st_.angle = x[1];
    double after = phi - teeth() * st_.angle;
    settle(s, st_, before, powered ? pullout(0) * std::sin(after) + s.load : s.load);
    if (powered) {
        auto period = static_cast<int64_t>(std::floor((after + M_PI) / (2 * M_PI)));
        slips_ += period - period_;
        period_ = period;
    }
}

} // namespace vb::plant
