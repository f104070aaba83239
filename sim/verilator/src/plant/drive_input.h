// SPDX-License-Identifier: GPL-2.0-or-later
//
// drive_input.h - what a drive makes of the firmware's output pins.
//
//  * BridgeInput: an H-bridge amplifier switched by PWM + direction pins or
//    by up/down pins (the hm2 pwmgen's output types 1-4, PDM included, and
//    the Pluto's UP/DN pins).  It keeps the exact time integral of the bridge
//    voltage between pin edges, so a model step gets the average voltage
//    over the step whatever the PWM frequency.
//  * StepInput: a step/direction (or quadrature) input with the drive's
//    timing limits.  It counts the steps the drive accepts and every timing
//    violation; a step whose timing is violated is lost (too short a pulse
//    or space: not seen) or taken the wrong way (direction setup or hold).
//
// Times are board ns.
#ifndef VBOARD_PLANT_DRIVE_INPUT_H
#define VBOARD_PLANT_DRIVE_INPUT_H

#include <cstdint>
#include <string>

namespace vb::plant {

class BridgeInput {
  public:
    enum class Mode { PwmDir, UpDown };

    // negative_level: the direction pin level that means negative voltage
    // (PwmDir).  In UpDown mode pin a drives +bus, pin b -bus, both or
    // neither 0 V.
    void configure(Mode mode, double bus_volts, bool negative_level, bool a0, bool b0, uint64_t t0);
    void set_a(bool level, uint64_t t) { change(level, b_, t); }
    void set_b(bool level, uint64_t t) { change(a_, level, t); }
    // Average bridge voltage since the last call (or configure), up to t.
    double take_average(uint64_t t);
    double volts_now() const { return v_; }

  private:
    double volts(bool a, bool b) const;
    void change(bool a, bool b, uint64_t t);

    Mode mode_ = Mode::PwmDir;
    double bus_ = 0;
    bool negative_ = true;
    bool a_ = false, b_ = false;
    double v_ = 0;        // voltage now
    double integral_ = 0; // V ns since t0_
    uint64_t t0_ = 0, last_ = 0;
};

// Timing limits of a step/direction input, ns.  A limit of 0 is not checked.
struct StepTiming {
    bool rising = true;     // the step happens on this edge of the step pin
    uint64_t min_high = 0;  // shortest high phase of the step pin the drive sees
    uint64_t min_low = 0;   // shortest low phase
    uint64_t dir_setup = 0; // direction stable before the step edge
    uint64_t dir_hold = 0;  // direction stable after the step edge
};

// A drive's data-sheet timing by model name: "G201", "G202", "G203V" (the
// Gecko drives of the integrator manual: G202 steps on the falling edge,
// 0.5 us low, 4.5 us high, 1 us setup, 20 us hold; G203V on the rising
// edge, 2 us low, 1 us high, 200 ns setup and hold; G201 as the G202 with
// 4 us high) and "generic" (nothing checked until the file gives limits).
// false when the name is unknown.
bool drive_timing(const std::string &model, StepTiming &t);

struct StepCounters {
    uint64_t edges = 0;        // active edges on the step pin (what was commanded)
    int64_t commanded = 0;     // the same, signed by the direction pin at the edge
    uint64_t accepted = 0;     // steps the drive took
    uint64_t short_high = 0;   // pulses too short: not seen
    uint64_t short_low = 0;    // spaces too short: the next pulse not seen
    uint64_t dir_setup = 0;    // direction changed too close before a step
    uint64_t dir_hold = 0;     // direction changed too close after a step
    uint64_t disabled = 0;     // steps while the drive was disabled (ignored)
    uint64_t quad_errors = 0;  // quadrature input: both lines changed at once
    uint64_t violations() const { return short_high + short_low + dir_setup + dir_hold; }
};

class StepInput {
  public:
    enum class Mode { StepDir, Quadrature };

    // dir_negative: the direction level that counts down.  A step is
    // counted when the phase after its edge ends (only then does the drive
    // know the pulse was long enough), in the direction latched at the edge.
    // Quadrature: the step pin is A, the direction pin B, each state change
    // is one step; a state shorter than min_high is a violation.
    void configure(Mode mode, const StepTiming &timing, bool dir_negative, bool step0, bool dir0,
                   uint64_t t0);
    void set_step(bool level, uint64_t t, bool enabled);
    void set_dir(bool level, uint64_t t, bool enabled);

    int64_t position() const { return position_; } // steps (microsteps) taken, signed
    const StepCounters &counters() const { return c_; }

  private:
    void quad(bool a, bool b, uint64_t t, bool enabled);

    Mode mode_ = Mode::StepDir;
    StepTiming tm_;
    bool dir_negative_ = true;
    bool step_ = false, dir_ = false;
    uint64_t step_change_ = 0;  // last step pin edge
    uint64_t dir_change_ = 0;   // last direction pin edge
    bool dir_changed_ = false;  // the direction pin has changed at least once
    int old_sign_ = 1;          // direction before the last direction change
    uint64_t edge_ = 0;         // time of the last step edge
    bool have_edge_ = false;
    bool pending_ = false;      // a step edge was seen, its pulse still runs
    bool last_counted_ = false; // the last pulse was counted (hold may flip it)
    int pulse_sign_ = 0;        // direction latched at the step edge
    int64_t position_ = 0;
    StepCounters c_;
};

} // namespace vb::plant

#endif // VBOARD_PLANT_DRIVE_INPUT_H
