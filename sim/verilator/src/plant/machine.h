// SPDX-License-Identifier: GPL-2.0-or-later
//
// machine.h - the machine behind a virtual board's pins (vboard --machine).
//
// A machine is a set of axes.  Each axis has a motor (DC brush servo behind
// an H-bridge amplifier, or a stepper behind a step/direction drive), the
// mechanics it moves (lead screw or spindle, mass, friction, gravity, hard
// stops), an optional motor encoder and linear scale, and switches (limits,
// home).  The machine is a PinAgent: it hears the firmware's output pins
// (PWM, direction, step, enables) at the exact board time they change, steps
// every model on a fixed grid of step_ns in board time, and puts encoder,
// switch and fault levels on the firmware's input pins.  Everything is
// deterministic: the same requests give the same pins, bit for bit.
#ifndef VBOARD_PLANT_MACHINE_H
#define VBOARD_PLANT_MACHINE_H

#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "drive_input.h"
#include "encoder.h"
#include "motor.h"
#include "pins.h"

namespace vb::plant {

// A pin and the level that means "active".
struct PinRef {
    int pin = -1;
    bool active_high = true;
    bool used() const { return pin >= 0; }
};

// A switch on an axis: active while from <= position <= to.
struct SwitchSpec {
    std::string name; // limit_min, limit_max, home
    PinRef pin;
    double from = 0, to = 0;
};

struct EncoderSpec {
    bool present = false;
    PinRef a, b, index;
    double counts_per_unit = 0; // per motor revolution (encoder) or per mm (scale)
    EncoderParams enc;
};

struct AxisSpec {
    std::string name;
    bool rotary = false;  // spindle / rotary axis: positions in revolutions
    double lead = 5;      // mm per screw revolution (linear)
    double gear = 1;      // motor revolutions per screw/spindle revolution
    double start = 0;     // initial position (mm or rev)
    bool stops = false;   // hard stops at stop_min / stop_max
    double stop_min = 0, stop_max = 0;
    std::vector<SwitchSpec> switches;

    enum class Motor { Dc, Stepper } motor = Motor::Dc;
    // DC servo
    DcMotorParams dc;
    BridgeInput::Mode bridge = BridgeInput::Mode::PwmDir;
    double bus_volts = 0;
    PinRef in_a, in_b;        // pwm/up and dir/down, or step and dir (a = A, b = B)
    bool negative_level = true; // the dir level meaning negative
    PinRef fault;
    uint64_t fault_after_ns = 0; // current held at the limit this long trips the fault (0: never)
    // stepper
    StepperParams stepper;
    int microsteps = 1;
    StepTiming timing;
    std::string drive_model;
    StepInput::Mode step_mode = StepInput::Mode::StepDir;

    PinRef enable;            // unused: always enabled
    EncoderSpec encoder;      // on the motor shaft
    EncoderSpec scale;        // on the slide (linear) or spindle
};

struct MachineSpec {
    std::string path;         // the file it came from
    std::string board, firmware;
    uint64_t step_ns = 1000;
    std::vector<AxisSpec> axes;
};

// The board's pin names under a firmware (Board::pin_names).
using PinNamesFn =
    std::function<std::vector<std::pair<std::string, std::string>>(const std::string &firmware)>;

// Read and check a machine file.  names: the board's pin names under the
// file's firmware; io_pins: the number of pins.  Errors name
// file:line and the key.
bool load_machine(const std::string &path, const std::string &board,
                  const PinNamesFn &names, uint32_t io_pins,
                  MachineSpec &spec, std::string &err);
// The same from a text (for tests): path is only used in messages.
bool parse_machine(const std::string &text, const std::string &path, const std::string &board,
                   const PinNamesFn &names, uint32_t io_pins, MachineSpec &spec, std::string &err);

class Machine final : public PinAgent {
  public:
    explicit Machine(const MachineSpec &spec);
    ~Machine() override;

    // Wire to the pins at board time now (the model grid starts there).
    void attach(PinBank &pins, uint64_t now);

    uint64_t next_event() const override { return next_; }
    void run(uint64_t t) override;
    void on_pin(uint32_t pin, bool level, uint64_t t) override;

    // A request from a host at host_time (0: a probe client) reached the
    // board at board time now: one trace row per distinct host time.
    void on_request(uint64_t host_time, uint64_t now);
    // Text commands of the VB_PLANT request (docs/vboard-machine.md):
    // "status", "trace PATH", "trace off", "reset".
    int command(const std::string &cmd, uint64_t now, std::string &reply, std::string &err);

    std::string status_json(uint64_t now) const;
    size_t axes() const { return units_.size(); }
    // Position of axis i in its unit (mm or rev), for tests.
    double position(size_t i) const;

  private:
    struct Unit;
    void step_grid(uint64_t t);
    void schedule();
    void write_trace_row(uint64_t host_time, uint64_t now);

    MachineSpec spec_;
    std::vector<std::unique_ptr<Unit>> units_;
    PinBank *pins_ = nullptr;
    // pin -> (unit, role) for the watched pins
    struct Listener {
        uint32_t unit;
        uint8_t role;
    };
    std::vector<std::vector<Listener>> listen_;
    uint64_t next_grid_ = 0, next_ = PinBank::kNever;
    std::unique_ptr<std::ofstream> trace_;
    std::string trace_path_;
    uint64_t trace_last_host_ = 0;
    uint64_t trace_rows_ = 0;
};

} // namespace vb::plant

#endif // VBOARD_PLANT_MACHINE_H
