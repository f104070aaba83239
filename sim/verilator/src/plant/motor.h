// SPDX-License-Identifier: GPL-2.0-or-later
//
// motor.h - the motors behind a virtual board's drives.
//
// Both motors turn a shaft that carries the whole mechanical load, referred
// to the motor (Shaft: inertia, viscous and Coulomb friction, a constant
// load torque such as gravity on a vertical axis).  The linear part of each
// model is integrated by exact zero-order-hold discretisation (zoh.h); the
// non-linear part (Coulomb friction and sticking, current limit, the
// stepper's sinusoidal torque and its torque-speed curve) is evaluated once
// per step and held over it.  Units are SI: V, A, ohm, H, N m, rad, rad/s,
// kg m^2, s.
#ifndef VBOARD_PLANT_MOTOR_H
#define VBOARD_PLANT_MOTOR_H

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "zoh.h"

namespace vb::plant {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The mechanical side, referred to the motor shaft.
struct Shaft {
    double inertia = 0;     // kg m^2, motor + reflected load (> 0)
    double viscous = 0;     // N m s/rad
    double coulomb = 0;     // N m, kinetic friction (also the breakaway torque)
    double load = 0;        // N m, constant torque on the shaft (gravity), signed
};

// The mechanical state every motor has.
struct ShaftState {
    double speed = 0; // rad/s
    double angle = 0; // rad
    bool stuck = true; // held by static friction
};

// Friction torque for one step: opposes motion, or balances the drive
// torque while it is below the breakaway level (sticking).  `drive` is the
// motor torque plus the load.
double friction_torque(const Shaft &s, const ShaftState &st, double drive);
// After a step: a shaft whose speed went through zero while the drive
// torque cannot break it free sticks (speed 0).
void settle_friction(const Shaft &s, ShaftState &st, double speed_before, double drive);

// ---- DC brush motor with its amplifier (H bridge) ---------------------------
struct DcMotorParams {
    double resistance = 1;   // armature R, ohm
    double inductance = 1e-3; // armature L, H
    double kt = 0.1;         // torque constant, N m/A
    double ke = 0.1;         // back-EMF constant, V s/rad
    Shaft shaft;
    double current_limit = kInf; // amplifier current limit, A
    double voltage_limit = kInf; // largest |V| the bridge applies, V
};

class DcMotor {
  public:
    // h: the step, s.
    void configure(const DcMotorParams &p, double h);
    // One step with the bridge's average voltage v over it; a disabled
    // bridge is open (no current flows: the shaft coasts).
    void step(double v, bool enabled);

    double current() const { return current_; }
    const ShaftState &state() const { return st_; }
    ShaftState &state() { return st_; }
    const DcMotorParams &params() const { return p_; }
    double torque() const { return p_.kt * current_; }
    // Steps in which the current limit held the current.
    uint64_t limited_steps() const { return limited_; }

  private:
    DcMotorParams p_;
    Zoh<3, 2> drive_; // x = [i, w, theta], u = [v, external torque]
    Zoh<2, 1> coast_; // x = [w, theta], u = [external torque]
    ShaftState st_;
    double current_ = 0;
    uint64_t limited_ = 0;
};

// ---- hybrid stepper motor driven by a microstepping current drive -----------
// Torque T(w) * sin(phi - Nr theta): phi is the electrical angle the drive's
// currents command (a quarter period per full step), Nr = full steps per
// rev / 4 rotor teeth, T(w) the pull-out torque at speed w (the
// torque-speed curve).  The rotor falls behind under load; beyond half an
// electrical period it slips to the next equilibrium: 4 full steps lost.
struct StepperParams {
    int full_steps = 200;                // per revolution
    // Torque-speed curve: (speed rad/s, pull-out torque N m), speeds
    // ascending, linear between points, flat beyond the ends.
    std::vector<std::pair<double, double>> curve = {{0.0, 1.0}};
    double damping = 0;                  // N m s/rad, electrical damping of the drive
    Shaft shaft;
};

class StepperMotor {
  public:
    void configure(const StepperParams &p, double h);
    // One step with the drive commanding electrical angle phi (rad); an
    // unpowered motor has no torque.
    void step(double phi, bool powered);

    const ShaftState &state() const { return st_; }
    ShaftState &state() { return st_; }
    const StepperParams &params() const { return p_; }
    double pullout(double speed) const;
    double teeth() const { return p_.full_steps / 4.0; }
    // Electrical periods the rotor slipped (signed: + = fell behind a
    // positive command); 4 full steps each.
    int64_t slips() const { return slips_; }
    // Reset the slip reference to the current lag (after a power-up).
    void rebase(double phi);

  private:
    StepperParams p_;
    Zoh<2, 1> mech_; // powered: x = [w, theta], u = [torque], with the drive damping
    Zoh<2, 1> free_; // unpowered: without it
    ShaftState st_;
    int64_t slips_ = 0;
    int64_t period_ = 0; // round(lag / 2 pi) at the last step
};

} // namespace vb::plant

#endif // VBOARD_PLANT_MOTOR_H
