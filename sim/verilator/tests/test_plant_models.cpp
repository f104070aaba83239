// SPDX-License-Identifier: GPL-2.0-or-later
//
// The plant models against analytic solutions (to 1e-9 relative): the
// armature's first-order current rise, a shaft's first-order speed rise
// and decay, the DC motor's second-order speed response (over- and
// underdamped, evaluated with complex roots), constant-acceleration
// kinematics, Coulomb friction's constant deceleration and stop; the
// current limit; the stepper's static lag under load and its slips; the
// bridge average of PWM/dir and up/down; step timing per drive data; the
// encoder's transition times and index.
#include <complex>
#include <vector>

#include "drive_input.h"
#include "encoder.h"
#include "motor.h"
#include "plant_test.h"

using namespace vb::plant;

namespace plant_test {
namespace {

constexpr double kH = 1e-6; // 1 us steps
constexpr double kRel = 1e-9;

void first_order_current()
{
    // Locked rotor (no electromechanical coupling): L di/dt = V - R i.
    DcMotorParams p;
    p.resistance = 1.5;
    p.inductance = 3e-3;
    p.kt = p.ke = 0;
    p.shaft.inertia = 1e-4;
    DcMotor m;
    m.configure(p, kH);
    const double v = 24, tau = p.inductance / p.resistance;
    for (int k = 1; k <= 10000; k++) {
        m.step(v, true);
        if (k % 997 == 0 || k == 1) {
            double t = k * kH;
            CHECK_REL(m.current(), v / p.resistance * (1 - std::exp(-t / tau)), kRel);
        }
    }
}

void first_order_shaft()
{
    // A constant torque against viscous friction: w = T/b (1 - e^(-bt/J)),
    // theta = T/b (t - J/b (1 - e^(-bt/J))).  Then the drive opens: decay.
    StepperParams p;
    p.shaft.inertia = 2e-4;
    p.shaft.viscous = 1e-3;
    p.shaft.load = 0.05;
    StepperMotor m;
    m.configure(p, kH);
    const double j = p.shaft.inertia, b = p.shaft.viscous, T = p.shaft.load, tm = j / b;
    for (int k = 1; k <= 50000; k++) {
        m.step(0, false);
        if (k % 4999 == 0) {
            double t = k * kH, e = std::exp(-t / tm);
            CHECK_REL(m.state().speed, T / b * (1 - e), kRel);
            CHECK_REL(m.state().angle, T / b * (t - tm * (1 - e)), kRel);
        }
    }
    // Coasting down: no load now (a DC motor with its bridge open).
    DcMotorParams d;
    d.shaft.inertia = j;
    d.shaft.viscous = b;
    DcMotor c;
    c.configure(d, kH);
    c.state().speed = 100;
    c.state().stuck = false;
    for (int k = 1; k <= 30000; k++) {
        c.step(0, false);
        if (k % 2999 == 0) {
            double t = k * kH, e = std::exp(-t / tm);
            CHECK_REL(c.state().speed, 100 * e, kRel);
            CHECK_REL(c.state().angle, 100 * tm * (1 - e), kRel);
            CHECK(c.current() == 0);
        }
    }
}

// Second-order speed response of a DC motor to a voltage step, from the
// characteristic roots s1, s2 of L J s^2 + (R J + L b) s + (R b + Kt Ke).
void second_order(double R, double L, double K, double J, double b)
{
    DcMotorParams p;
    p.resistance = R;
    p.inductance = L;
    p.kt = p.ke = K;
    p.shaft.inertia = J;
    p.shaft.viscous = b;
    DcMotor m;
    m.configure(p, kH);
    const double v = 12;
    using C = std::complex<double>;
    double a2 = L * J, a1 = R * J + L * b, a0 = R * b + K * K;
    C disc = std::sqrt(C(a1 * a1 - 4 * a2 * a0, 0));
    C s1 = (-a1 + disc) / (2 * a2), s2 = (-a1 - disc) / (2 * a2);
    double wss = K * v / a0;
    for (int k = 1; k <= 40000; k++) {
        m.step(v, true);
        if (k % 1999 == 0) {
            double t = k * kH;
            C e1 = std::exp(s1 * t), e2 = std::exp(s2 * t);
            double w = wss * (1.0 - ((s2 * e1 - s1 * e2) / (s2 - s1)).real());
            double dw = (wss * (-s1 * s2) * (e1 - e2) / (s2 - s1)).real();
            double i = (J * dw + b * w) / K;
            // the angle: integral of w
            double th = wss * (t - ((s2 / s1 * (e1 - 1.0) - s1 / s2 * (e2 - 1.0)) / (s2 - s1)).real());
            // relative to the response's scale (the current crosses zero
            // when it is underdamped)
            CHECK_CLOSE(m.state().speed, w, kRel, wss);
            CHECK_CLOSE(m.current(), i, kRel, v / R);
            CHECK_CLOSE(m.state().angle, th, kRel, wss * t);
        }
    }
}

void constant_acceleration()
{
    // No friction, a constant torque: theta = T t^2 / 2J, w = T t / J
    // (gravity on a coasting DC motor's shaft).
    DcMotorParams p;
    p.shaft.inertia = 3e-4;
    p.shaft.load = -0.12;
    DcMotor m;
    m.configure(p, kH);
    m.state().stuck = false;
    const double a = p.shaft.load / p.shaft.inertia;
    for (int k = 1; k <= 20000; k++) {
        m.step(0, false);
        if (k % 1999 == 0) {
            double t = k * kH;
            CHECK_REL(m.state().speed, a * t, kRel);
            CHECK_REL(m.state().angle, a * t * t / 2, kRel);
        }
    }
}

void coulomb_friction()
{
    // A shaft spinning at w0 against Coulomb friction only decelerates at
    // Tc/J and stops at t = w0 J / Tc, angle w0^2 J / (2 Tc); then it sticks.
    DcMotorParams p;
    p.shaft.inertia = 1e-4;
    p.shaft.coulomb = 0.02;
    DcMotor m;
    m.configure(p, kH);
    const double w0 = 50, dec = p.shaft.coulomb / p.shaft.inertia, tstop = w0 / dec;
    m.state().speed = w0;
    m.state().stuck = false;
    int k = 0;
    for (; (k + 1) * kH < tstop; k++) {
        m.step(0, false);
        double t = (k + 1) * kH;
        if (k % 1000 == 0) {
            CHECK_REL(m.state().speed, w0 - dec * t, kRel);
            CHECK_REL(m.state().angle, w0 * t - dec * t * t / 2, kRel);
        }
    }
    for (int j = 0; j < 5000; j++)
        m.step(0, false);
    CHECK(m.state().speed == 0 && m.state().stuck);
    CHECK(std::fabs(m.state().angle - w0 * w0 / (2 * dec)) <= w0 * kH);
    // A drive torque below breakaway leaves it stuck.
    p.shaft.load = 0.019;
    m.configure(p, kH);
    double at = m.state().angle;
    for (int j = 0; j < 1000; j++)
        m.step(0, false);
    CHECK(m.state().speed == 0 && m.state().angle == at);
}

void current_limit()
{
    DcMotorParams p;
    p.resistance = 0.5;
    p.inductance = 1e-3;
    p.kt = p.ke = 0;
    p.shaft.inertia = 1e-4;
    p.current_limit = 8;
    p.voltage_limit = 40;
    DcMotor m;
    m.configure(p, kH);
    for (int k = 0; k < 20000; k++)
        m.step(100, true); // clamped to 40 V: 80 A without the limit
    CHECK(m.current() == 8);
    CHECK(m.limited_steps() > 0);
    for (int k = 0; k < 20000; k++)
        m.step(-1, true); // below the limit: the RL step response again
    CHECK_REL(m.current(), -2 + 10 * std::exp(-20000 * kH * p.resistance / p.inductance), 1e-9);
}

void stepper_static_and_slip()
{
    StepperParams p;
    p.full_steps = 200;
    p.curve = {{0, 1.0}, {100, 0.5}};
    p.damping = 0.05;
    p.shaft.inertia = 1e-4;
    p.shaft.load = 0.5; // half the holding torque
    StepperMotor m;
    m.configure(p, kH);
    CHECK_REL(m.pullout(50), 0.75, 1e-15);
    CHECK_REL(m.pullout(-200), 0.5, 1e-15);
    for (int k = 0; k < 400000; k++)
        m.step(0, true);
    // Equilibrium: T sin(-Nr theta) + load = 0 -> theta = asin(0.5) / 50.
    CHECK_REL(m.state().angle, std::asin(0.5) / 50, 1e-9);
    CHECK(m.slips() == 0);
    // Beyond the holding torque it slips, electrical period after period.
    p.shaft.load = 1.5;
    m.configure(p, kH);
    for (int k = 0; k < 200000; k++)
        m.step(0, true);
    CHECK(m.slips() < -2);
    CHECK(m.state().angle > 4 * 2 * M_PI / 50);
}

void bridge()
{
    BridgeInput b;
    // PWM/dir, direction pin high = negative: 25 % duty negative.
    b.configure(BridgeInput::Mode::PwmDir, 48, true, false, true, 1000);
    for (uint64_t t = 1000; t < 1000 + 50000; t += 1000) {
        b.set_a(true, t);
        b.set_a(false, t + 250);
    }
    CHECK_REL(b.take_average(51000), -12, 1e-12);
    // up/down: up 30 %, down 10 %: +20 % of the bus
    b.configure(BridgeInput::Mode::UpDown, 24, true, false, false, 0);
    for (uint64_t t = 0; t < 100000; t += 1000) {
        b.set_a(true, t);
        b.set_a(false, t + 300);
        b.set_b(true, t + 500);
        b.set_b(false, t + 600);
    }
    CHECK_REL(b.take_average(100000), 4.8, 1e-12);
}

// Pulses on a step input: (step edge, pulse width, space) per step.
void step_timing()
{
    StepTiming g;
    CHECK(drive_timing("G203V", g) && g.rising && g.min_high == 1000 && g.min_low == 2000 &&
          g.dir_setup == 200 && g.dir_hold == 200);
    CHECK(drive_timing("G202", g) && !g.rising && g.min_low == 500 && g.min_high == 4500 &&
          g.dir_hold == 20000);
    CHECK(!drive_timing("G999", g));
    drive_timing("G203V", g);
    StepInput s;
    s.configure(StepInput::Mode::StepDir, g, true, false, false, 0);
    uint64_t t = 10000;
    auto pulse = [&](uint64_t high, uint64_t low) {
        s.set_step(true, t, true);
        s.set_step(false, t + high, true);
        t += high + low;
    };
    for (int i = 0; i < 10; i++)
        pulse(1000, 2000); // exactly the limits: all taken
    CHECK(s.position() == 10 && s.counters().violations() == 0);
    pulse(900, 5000); // too short a pulse: lost
    CHECK(s.position() == 10 && s.counters().short_high == 1);
    pulse(1000, 1500); // the space after it is too short: the next one is lost
    pulse(1000, 5000);
    CHECK(s.position() == 11 && s.counters().short_low == 1);
    // Direction change 100 ns before the step: the drive steps the old way.
    s.set_dir(true, t - 100, true);
    pulse(1000, 5000);
    CHECK(s.position() == 12 && s.counters().dir_setup == 1);
    // ... and with 200 ns it counts down.
    pulse(1000, 5000);
    CHECK(s.position() == 11);
    // Direction back 150 ns after a step edge: that step goes up instead.
    s.set_step(true, t, true);
    s.set_dir(false, t + 150, true);
    s.set_step(false, t + 1000, true);
    t += 6000;
    CHECK(s.position() == 12 && s.counters().dir_hold == 1);
    // disabled drive: ignored, timing not checked (its inputs are off)
    s.set_step(true, t, false);
    s.set_dir(true, t, false);
    s.set_step(false, t + 10, false);
    CHECK(s.position() == 12 && s.counters().disabled == 1 && s.counters().violations() == 4);
    CHECK(s.counters().edges == 17);

    // Quadrature input: A leads B up.
    StepInput qd;
    qd.configure(StepInput::Mode::Quadrature, StepTiming{}, false, false, false, 0);
    qd.set_step(true, 100, true);
    qd.set_dir(true, 200, true);
    qd.set_step(false, 300, true);
    qd.set_dir(false, 400, true);
    CHECK(qd.position() == 4);
    qd.set_dir(true, 500, true); // B leads: down
    CHECK(qd.position() == 3);
}

void encoder()
{
    EncoderParams p;
    p.counts_per_rev = 8;
    p.index_count = 2;
    Encoder e;
    e.configure(p, 0.5, 0);
    CHECK(e.count() == 0 && !e.a() && !e.b() && !e.index());
    // 0.5 -> 4.0 counts over the next 1000 ns: boundaries 1, 2, 3, 4 at
    // f = (k - 0.5) / 3.5.
    e.plan(4.0, 1000, 1000);
    std::vector<uint64_t> times;
    std::vector<int> ab;
    while (e.next_event() != UINT64_MAX) {
        uint64_t t = e.next_event();
        e.run(t);
        times.push_back(t);
        ab.push_back(e.a() * 2 + e.b());
        if (e.count() == 2)
            CHECK(e.index());
        else
            CHECK(!e.index());
    }
    CHECK(times.size() == 4);
    for (size_t k = 0; k < times.size(); k++)
        CHECK(times[k] == 1000 + static_cast<uint64_t>((k + 0.5) / 3.5 * 1000));
    // A leads B: 00 -> 10 -> 11 -> 01 -> 00
    CHECK(ab == (std::vector<int>{2, 3, 1, 0}));
    CHECK(e.count() == 4);
    // Backwards across the index.
    e.plan(1.2, 2000, 1000);
    while (e.next_event() != UINT64_MAX)
        e.run(e.next_event());
    CHECK(e.count() == 1);

    // Glitches: a Poisson process of the mean rate, the same for the same seed.
    p.glitch_rate = 1e4;
    p.glitch_ns = 50;
    Encoder g1, g2;
    g1.configure(p, 0, 0);
    g2.configure(p, 0, 0);
    std::vector<uint64_t> t1;
    while (g1.next_event() < 1000000000ull) {
        uint64_t t = g1.next_event();
        g1.run(t);
        t1.push_back(t);
        g2.run(t);
        CHECK(g1.a() == g2.a() && g1.b() == g2.b());
    }
    CHECK(g1.glitches() > 9700 && g1.glitches() < 10300); // 1e4 expected, sd 100
    CHECK(g1.count() == 0);
}

} // namespace

void models()
{
    first_order_current();
    first_order_shaft();
    second_order(1.2, 2.5e-3, 0.08, 1.5e-4, 1e-4); // overdamped
    second_order(0.2, 5e-3, 0.02, 1e-4, 1e-6);     // underdamped
    constant_acceleration();
    coulomb_friction();
    current_limit();
    stepper_static_and_slip();
    bridge();
    step_timing();
    encoder();
}

} // namespace plant_test
