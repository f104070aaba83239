// SPDX-License-Identifier: GPL-2.0-or-later
//
// A machine on a bare pin bank, pins driven by the test as the firmware
// would: a PWM-driven servo reaches the speed of the linear model's DC
// gain (the mean of a linear system's periodic response is its response
// to the mean input), its encoder pins count what the shaft turned, the
// amplifier's enable and the limit switch work; a stepper given step
// pulses within the G203V's timing ends on the commanded step; the same
// run twice gives the same status, byte for byte.
#include <string>
#include <vector>

#include "machine.h"
#include "pins.h"
#include "plant_test.h"

using namespace vb::plant;

namespace plant_test {
namespace {

const char *kServo = R"(
board = "t"
[[axis]]
name = "x"
lead_mm = 5
mass_kg = 10
viscous_n_s_per_m = 2000
limit_max = { pin = 6, at_mm = 20, active = "low" }
[axis.motor]
type = "dc"
resistance_ohm = 1.0
inductance_h = 2e-3
kt_nm_per_a = 0.1
ke_v_s_per_rad = 0.1
inertia_kg_m2 = 1e-4
[axis.amplifier]
a = 0
b = 1
bus_v = 24
enable = { pin = 2, active = "low" }
[axis.encoder]
a = 3
b = 4
index = 5
counts_per_rev = 1000
)";

const char *kStepper = R"(
board = "t"
[[axis]]
name = "y"
lead_mm = 4
mass_kg = 20
friction_n = 50
[axis.motor]
type = "stepper"
inertia_kg_m2 = 5e-5
damping_nm_s_per_rad = 0.01
torque_curve = [[0, 1.5], [1000, 1.0], [3000, 0.3]]
[axis.drive]
model = "G203V"
microsteps = 10
step = 0
dir = 1
)";

struct Rig {
    vb::PinBank pins{16};
    std::unique_ptr<Machine> m;
    uint32_t out[1] = {0}, oe[1] = {0};

    explicit Rig(const char *text)
    {
        MachineSpec s;
        std::string err;
        auto none = [](const std::string &) {
            return std::vector<std::pair<std::string, std::string>>{};
        };
        bool ok = parse_machine(text, "t.toml", "t", none, 16, s, err);
        CHECK(ok);
        if (!ok)
            std::fprintf(stderr, "%s\n", err.c_str());
        m = std::make_unique<Machine>(s);
        m->attach(pins, 0);
    }
    // The firmware drives pin p to v at time t (after everything before t).
    void set(uint32_t p, bool v, uint64_t t)
    {
        pins.run_events(t);
        out[0] = (out[0] & ~(1u << p)) | (uint32_t(v) << p);
        oe[0] |= 1u << p;
        pins.set_fpga(out, oe, t);
    }
};

void servo()
{
    Rig r(kServo);
    r.set(2, false, 0); // enable (active low)
    r.set(1, false, 0); // positive
    // 20 kHz PWM, 50 %: 12 V average for 0.3 s.
    const uint64_t per = 50000;
    double sum = 0;
    int n = 0;
    uint64_t t = 0;
    for (; t < 300000000; t += per) {
        r.set(0, true, t);
        r.set(0, false, t + per / 2);
        if (t >= 299000000) {
            // the speed over the last millisecond, at every grid step
            for (uint64_t k = t; k < t + per; k += 1000) {
                r.pins.run_events(k);
                sum += std::stod(r.m->status_json(k).substr(r.m->status_json(k).find("\"velocity\": ") + 12));
                n++;
            }
        }
    }
    // DC gain: w = Kt V / (R b + Kt Ke), b = 2000 (lead/2pi)^2; in mm/s.
    double rr = 5e-3 / (2 * M_PI), b = 2000 * rr * rr, w = 0.1 * 12 / (1.0 * b + 0.01);
    double v_mm = w * rr * 1e3;
    CHECK_REL(sum / n, v_mm, 1e-4);
    // Encoder pins: A rose once per 4 counts of shaft travel.
    std::vector<vb_pin> pr;
    std::string err;
    r.pins.probe(3, 3, t, pr, err);
    double counts = r.m->position(0) / 5 * 1000;
    CHECK(std::fabs(pr[0].rising - counts / 4) <= 1.5);
    CHECK(std::fabs(pr[2].rising - counts / 1000) <= 1); // index once per rev
    // limit switch at 20 mm: active low once beyond
    CHECK((r.m->position(0) > 20) == !r.pins.level(6));
    // disable: the shaft coasts down (viscous only: exponentially)
    double v0 = v_mm;
    r.set(2, true, t);
    r.pins.run_events(t + 100000000);
    std::string st = r.m->status_json(t + 100000000);
    CHECK_CONTAINS(st, "\"enabled\": false");
    CHECK_CONTAINS(st, "\"current\": 0,");
    double v1 = std::stod(st.substr(st.find("\"velocity\": ") + 12));
    CHECK(v1 >= 0 && v1 < v0 * 0.5);
}

std::string stepper_run(int steps, uint64_t dirsetup)
{
    Rig r(kStepper);
    r.set(0, false, 0);
    r.set(1, false, 0);
    uint64_t t = 1000000;
    // ramp up to 20 kHz and back, 1 us pulses, 2+ us spaces
    for (int i = 0; i < steps; i++) {
        double f = 2000 + 18000 * std::min(1.0, std::min(i, steps - i) / 400.0);
        uint64_t per = static_cast<uint64_t>(1e9 / f);
        r.set(0, true, t);
        r.set(0, false, t + 1000);
        t += per;
    }
    // and back by 10 steps after a direction change
    r.set(1, true, t);
    t += dirsetup;
    for (int i = 0; i < 10; i++) {
        r.set(0, true, t);
        r.set(0, false, t + 1000);
        t += 500000;
    }
    r.pins.run_events(t + 200000000);
    return r.m->status_json(t + 200000000);
}

void stepper()
{
    std::string a = stepper_run(4000, 20000);
    CHECK_CONTAINS(a, "\"commanded\": 3990, \"accepted\": 4010, \"drive_position\": 3990, \"taken\": 3990, \"missed\": 0, \"violations\": 0");
    // 3990 microsteps of 1/2000 rev at 4 mm/rev
    double pos = std::stod(a.substr(a.find("\"position\": ") + 12));
    CHECK(std::fabs(pos - 3990 * 4.0 / 2000) < 4.0 / 2000 / 2);
    CHECK(stepper_run(4000, 20000) == a); // deterministic
    // direction changed 100 ns before the step: one step the wrong way
    std::string b = stepper_run(4000, 100);
    CHECK_CONTAINS(b, "\"drive_position\": 3992, \"taken\": 3992, \"missed\": -2, \"violations\": 1");
    CHECK_CONTAINS(b, "\"dir_setup\": 1");
}

const char *kStop = R"(
board = "t"
[[axis]]
name = "x"
lead_mm = 5
mass_kg = 10
hard_stops_mm = [-1, 1]
[axis.motor]
type = "dc"
resistance_ohm = 1.0
inductance_h = 1e-3
kt_nm_per_a = 0.1
ke_v_s_per_rad = 0.1
inertia_kg_m2 = 1e-4
[axis.amplifier]
a = 0
b = 1
bus_v = 24
current_limit_a = 5
enable = { pin = 2, active = "low" }
fault = { pin = 7, active = "low", after_ms = 20 }
)";

// Full voltage into a hard stop: the slide stops dead at 1 mm, the current
// rises to the amplifier's limit, 20 ms later the amplifier trips (fault
// pin active, bridge open, current 0); an enable edge clears it.
void hard_stop_and_fault()
{
    Rig r(kStop);
    r.set(2, false, 0);
    r.set(1, false, 0);
    r.set(0, true, 0); // 100 % positive
    CHECK(r.pins.level(7)); // fault inactive (high)
    r.pins.run_events(100000000);
    std::string st = r.m->status_json(100000000);
    CHECK_CONTAINS(st, "\"position\": 1,");
    CHECK_CONTAINS(st, "\"velocity\": 0,");
    CHECK_CONTAINS(st, "\"stop_hits\": 1,");
    CHECK_CONTAINS(st, "\"fault\": true");
    CHECK_CONTAINS(st, "\"current\": 0,");
    CHECK(!r.pins.level(7));
    // when did it trip?  the current reached 5 A within a few ms of the
    // stop; the fault came after_ms later, well inside the 100 ms
    double at = std::stod(st.substr(st.find("\"current_limited_steps\": ") + 25));
    CHECK(at >= 20000 && at <= 21000); // 20 ms of 1 us steps at the limit, then open
    r.set(2, true, 100000000); // disable ...
    r.set(2, false, 100001000); // ... and enable again: cleared
    CHECK(r.pins.level(7));
    r.pins.run_events(100100000);
    CHECK_CONTAINS(r.m->status_json(100100000), "\"fault\": false");
}

} // namespace

void machine()
{
    servo();
    stepper();
    hard_stop_and_fault();
}

} // namespace plant_test
