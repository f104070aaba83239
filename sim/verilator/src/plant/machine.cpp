// SPDX-License-Identifier: GPL-2.0-or-later
//
// machine.cpp - the machine's run time: pins in, models on the step grid,
// pins out, status and trace (machine.h).
#include "machine.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace vb::plant {

namespace {
enum Role : uint8_t { kInA = 0, kInB = 1, kEnable = 2 };

std::string num(double v)
{
    char b[40];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}

std::string q(const std::string &s)
{
    std::string out = "\"";
    for (char c : s)
        out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    return out + "\"";
}
} // namespace

struct Machine::Unit {
    AxisSpec s;
    DcMotor dc;
    StepperMotor st;
    BridgeInput bridge;
    StepInput steps;
    Encoder enc, scale;
    double rad_per_unit = 1;
    bool enabled = true;
    bool fault = false;
    bool at_limit = false;
    uint64_t limit_since = 0;
    uint64_t stop_hits = 0;
    bool at_stop = false;
    std::vector<bool> sw;

    bool dc_motor() const { return s.motor == AxisSpec::Motor::Dc; }
    const ShaftState &shaft() const { return dc_motor() ? dc.state() : st.state(); }
    ShaftState &shaft() { return dc_motor() ? dc.state() : st.state(); }
    double position() const { return s.start + shaft().angle / rad_per_unit; }
    double velocity() const { return shaft().speed / rad_per_unit; }
    double phi() const { return steps.position() * (M_PI / 2) / s.microsteps; }
    // Rotor position in microsteps (what the drive's steps moved it to).
    int64_t taken() const
    {
        return static_cast<int64_t>(std::llround(st.teeth() * st.state().angle * 2.0 *
                                                  s.microsteps / M_PI));
    }
    double enc_counts() const
    {
        return shaft().angle / (2 * M_PI) * s.encoder.counts_per_unit;
    }
    // a scale counts from position 0 of the axis (mm, or rev on a spindle)
    double scale_counts() const { return position() * s.scale.counts_per_unit; }
};

Machine::Machine(const MachineSpec &spec) : spec_(spec)
{
    double h = static_cast<double>(spec.step_ns) * 1e-9;
    for (const AxisSpec &a : spec.axes) {
        auto u = std::make_unique<Unit>();
        u->s = a;
        u->rad_per_unit = 2 * M_PI * a.gear / (a.rotary ? 1.0 : a.lead);
        if (a.motor == AxisSpec::Motor::Dc)
            u->dc.configure(a.dc, h);
        else
            u->st.configure(a.stepper, h);
        u->sw.assign(a.switches.size(), false);
        units_.push_back(std::move(u));
    }
}

Machine::~Machine() = default;

void Machine::attach(PinBank &pins, uint64_t now)
{
    pins_ = &pins;
    listen_.assign(pins.size(), {});
    auto listen = [&](const PinRef &r, uint32_t unit, uint8_t role) {
        if (!r.used())
            return;
        listen_[r.pin].push_back(Listener{unit, role});
        pins.watch(static_cast<uint32_t>(r.pin));
    };
    for (uint32_t i = 0; i < units_.size(); i++) {
        Unit &u = *units_[i];
        const AxisSpec &s = u.s;
        listen(s.in_a, i, kInA);
        listen(s.in_b, i, kInB);
        listen(s.enable, i, kEnable);
        bool a = s.in_a.used() && pins.level(static_cast<uint32_t>(s.in_a.pin));
        bool b = s.in_b.used() && pins.level(static_cast<uint32_t>(s.in_b.pin));
        if (s.enable.used())
            u.enabled = pins.level(static_cast<uint32_t>(s.enable.pin)) == s.enable.active_high;
        if (u.dc_motor())
            u.bridge.configure(s.bridge, s.bus_volts, s.negative_level, a, b, now);
        else
            u.steps.configure(s.step_mode, s.timing, s.negative_level, a, b, now);
        u.st.rebase(0);
        if (s.encoder.present) {
            u.enc.configure(s.encoder.enc, u.enc_counts(), now);
            pins.own(s.encoder.a.pin, u.enc.a(), now);
            pins.own(s.encoder.b.pin, u.enc.b(), now);
            if (s.encoder.index.used())
                pins.own(s.encoder.index.pin, u.enc.index() == s.encoder.index.active_high, now);
        }
        if (s.scale.present) {
            u.scale.configure(s.scale.enc, u.scale_counts(), now);
            pins.own(s.scale.a.pin, u.scale.a(), now);
            pins.own(s.scale.b.pin, u.scale.b(), now);
            if (s.scale.index.used())
                pins.own(s.scale.index.pin, u.scale.index() == s.scale.index.active_high, now);
        }
        double pos = u.position();
        for (size_t k = 0; k < s.switches.size(); k++) {
            const SwitchSpec &w = s.switches[k];
            u.sw[k] = pos >= w.from && pos <= w.to;
            pins.own(w.pin.pin, u.sw[k] == w.pin.active_high, now);
        }
        if (s.fault.used())
            pins.own(s.fault.pin, !s.fault.active_high, now);
    }
    next_grid_ = now + spec_.step_ns;
    schedule();
    pins.set_agent(this);
}

void Machine::schedule()
{
    uint64_t n = next_grid_;
    for (const auto &u : units_) {
        n = std::min(n, u->enc.next_event());
        n = std::min(n, u->scale.next_event());
    }
    next_ = n;
}

void Machine::on_pin(uint32_t pin, bool level, uint64_t t)
{
    for (const Listener &l : listen_[pin]) {
        Unit &u = *units_[l.unit];
        bool en = u.enabled && !u.fault;
        switch (l.role) {
        case kInA:
            if (u.dc_motor())
                u.bridge.set_a(level, t);
            else
                u.steps.set_step(level, t, en);
            break;
        case kInB:
            if (u.dc_motor())
                u.bridge.set_b(level, t);
            else
                u.steps.set_dir(level, t, en);
            break;
        case kEnable: {
            bool on = level == u.s.enable.active_high;
            if (on && !u.enabled) {
                u.fault = false; // an enable edge clears a latched fault
                if (u.s.fault.used())
                    pins_->agent_set(u.s.fault.pin, !u.s.fault.active_high, t);
                if (!u.dc_motor())
                    u.st.rebase(u.phi());
            }
            u.enabled = on;
            break;
        }
        }
    }
}

void Machine::step_grid(uint64_t t)
{
    uint64_t h = spec_.step_ns;
    for (auto &up : units_) {
        Unit &u = *up;
        const AxisSpec &s = u.s;
        bool en = u.enabled && !u.fault;
        if (u.dc_motor()) {
            double v = u.bridge.take_average(t);
            uint64_t limited = u.dc.limited_steps();
            u.dc.step(v, en);
            bool at_limit = u.dc.limited_steps() != limited;
            if (s.fault.used() && s.fault_after_ns) {
                if (!at_limit) {
                    u.at_limit = false;
                } else if (!u.at_limit) {
                    u.at_limit = true;
                    u.limit_since = t;
                } else if (t - u.limit_since >= s.fault_after_ns && !u.fault) {
                    u.fault = true;
                    pins_->agent_set(s.fault.pin, s.fault.active_high, t);
                }
            }
        } else {
            u.st.step(u.phi(), en);
        }
        // Hard stops: the slide stops dead (an inelastic stop).
        if (s.stops) {
            double pos = u.position();
            ShaftState &sh = u.shaft();
            bool hit = false;
            if (pos < s.stop_min) {
                sh.angle = (s.stop_min - s.start) * u.rad_per_unit;
                sh.speed = std::max(sh.speed, 0.0);
                hit = true;
            } else if (pos > s.stop_max) {
                sh.angle = (s.stop_max - s.start) * u.rad_per_unit;
                sh.speed = std::min(sh.speed, 0.0);
                hit = true;
            }
            if (hit && !u.at_stop)
                u.stop_hits++;
            u.at_stop = hit;
        }
        double pos = u.position();
        for (size_t k = 0; k < s.switches.size(); k++) {
            const SwitchSpec &w = s.switches[k];
            bool on = pos >= w.from && pos <= w.to;
            if (on != u.sw[k]) {
                u.sw[k] = on;
                pins_->agent_set(w.pin.pin, on == w.pin.active_high, t);
            }
        }
        if (s.encoder.present)
            u.enc.plan(u.enc_counts(), t, h);
        if (s.scale.present)
            u.scale.plan(u.scale_counts(), t, h);
    }
    next_grid_ = t + h;
}

void Machine::run(uint64_t t)
{
    while (next_ <= t) {
        uint64_t now = next_;
        if (next_grid_ <= now)
            step_grid(now);
        for (auto &up : units_) {
            Unit &u = *up;
            const AxisSpec &s = u.s;
            if (u.enc.next_event() <= now) {
                u.enc.run(now);
                pins_->agent_set(s.encoder.a.pin, u.enc.a(), now);
                pins_->agent_set(s.encoder.b.pin, u.enc.b(), now);
                if (s.encoder.index.used())
                    pins_->agent_set(s.encoder.index.pin,
                                     u.enc.index() == s.encoder.index.active_high, now);
            }
            if (u.scale.next_event() <= now) {
                u.scale.run(now);
                pins_->agent_set(s.scale.a.pin, u.scale.a(), now);
                pins_->agent_set(s.scale.b.pin, u.scale.b(), now);
                if (s.scale.index.used())
                    pins_->agent_set(s.scale.index.pin,
                                     u.scale.index() == s.scale.index.active_high, now);
            }
        }
        schedule();
    }
}

double Machine::position(size_t i) const { return units_[i]->position(); }

void Machine::on_request(uint64_t host_time, uint64_t now)
{
    if (!trace_ || host_time == 0 || host_time == trace_last_host_)
        return;
    trace_last_host_ = host_time;
    write_trace_row(host_time, now);
}

void Machine::write_trace_row(uint64_t host_time, uint64_t now)
{
    std::string row = std::to_string(host_time) + "," + std::to_string(now);
    for (const auto &up : units_) {
        const Unit &u = *up;
        row += "," + num(u.position()) + "," + num(u.velocity());
        if (u.dc_motor())
            row += "," + num(u.dc.current());
        else
            row += "," + std::to_string(u.steps.position()) + "," + std::to_string(u.taken());
    }
    *trace_ << row << '\n';
    trace_rows_++;
}

int Machine::command(const std::string &cmd, uint64_t now, std::string &reply, std::string &err)
{
    if (cmd == "status") {
        reply = status_json(now);
        return 0;
    }
    if (cmd == "trace off") {
        if (!trace_) {
            err = "plant: trace off: no trace is running";
            return -EINVAL;
        }
        trace_->flush();
        bool ok = static_cast<bool>(*trace_);
        trace_.reset();
        reply = "{\"rows\": " + std::to_string(trace_rows_) + "}";
        if (!ok) {
            err = "plant: trace " + trace_path_ + ": write failed";
            return -EIO;
        }
        return 0;
    }
    if (cmd.compare(0, 6, "trace ") == 0) {
        std::string path = cmd.substr(6);
        if (trace_) {
            err = "plant: a trace is already running (" + trace_path_ + "); stop it first";
            return -EBUSY;
        }
        auto f = std::make_unique<std::ofstream>(path, std::ios::out | std::ios::trunc);
        if (!*f) {
            err = "plant: trace: cannot open " + path + " for writing: " + std::strerror(errno);
            return -EIO;
        }
        std::string head = "host_ns,board_ns";
        for (const auto &up : units_) {
            const std::string &n = up->s.name;
            head += "," + n + ".pos," + n + ".vel";
            head += up->dc_motor() ? "," + n + ".current" : "," + n + ".steps," + n + ".taken";
        }
        *f << head << '\n';
        trace_ = std::move(f);
        trace_path_ = path;
        trace_last_host_ = 0;
        trace_rows_ = 0;
        reply = "{}";
        return 0;
    }
    err = "plant: unknown command '" + cmd + "' (status, trace PATH, trace off)";
    return -EINVAL;
}

std::string Machine::status_json(uint64_t now) const
{
    std::string j = "{\"time_ns\": " + std::to_string(now) + ", \"file\": " + q(spec_.path) +
                    ", \"axes\": [";
    for (size_t i = 0; i < units_.size(); i++) {
        const Unit &u = *units_[i];
        const AxisSpec &s = u.s;
        j += i ? ", " : "";
        j += "{\"name\": " + q(s.name) + ", \"motor\": " + q(u.dc_motor() ? "dc" : "stepper") +
             ", \"unit\": " + q(s.rotary ? "rev" : "mm") + ", \"position\": " + num(u.position()) +
             ", \"velocity\": " + num(u.velocity()) +
             ", \"enabled\": " + (u.enabled ? "true" : "false") +
             ", \"fault\": " + (u.fault ? "true" : "false") +
             ", \"stop_hits\": " + std::to_string(u.stop_hits) + ", \"switches\": {";
        for (size_t k = 0; k < s.switches.size(); k++)
            j += (k ? ", " : "") + q(s.switches[k].name) + ": " + (u.sw[k] ? "true" : "false");
        j += "}";
        if (u.dc_motor()) {
            j += ", \"current\": " + num(u.dc.current()) +
                 ", \"current_limited_steps\": " + std::to_string(u.dc.limited_steps());
        } else {
            const StepCounters &c = u.steps.counters();
            int64_t taken = u.taken();
            j += ", \"steps\": {\"edges\": " + std::to_string(c.edges) +
                 ", \"commanded\": " + std::to_string(c.commanded) +
                 ", \"accepted\": " + std::to_string(c.accepted) +
                 ", \"drive_position\": " + std::to_string(u.steps.position()) +
                 ", \"taken\": " + std::to_string(taken) +
                 ", \"missed\": " + std::to_string(c.commanded - taken) +
                 ", \"violations\": " + std::to_string(c.violations()) +
                 ", \"short_high\": " + std::to_string(c.short_high) +
                 ", \"short_low\": " + std::to_string(c.short_low) +
                 ", \"dir_setup\": " + std::to_string(c.dir_setup) +
                 ", \"dir_hold\": " + std::to_string(c.dir_hold) +
                 ", \"while_disabled\": " + std::to_string(c.disabled) +
                 ", \"quad_errors\": " + std::to_string(c.quad_errors) +
                 ", \"stall_slips\": " + std::to_string(u.st.slips()) + "}";
        }
        if (s.encoder.present)
            j += ", \"encoder\": {\"count\": " + std::to_string(u.enc.count()) +
                 ", \"glitches\": " + std::to_string(u.enc.glitches()) + "}";
        if (s.scale.present)
            j += ", \"scale\": {\"count\": " + std::to_string(u.scale.count()) +
                 ", \"glitches\": " + std::to_string(u.scale.glitches()) + "}";
        j += "}";
    }
    return j + "]}";
}

} // namespace vb::plant
