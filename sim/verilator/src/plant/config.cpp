// SPDX-License-Identifier: GPL-2.0-or-later
//
// config.cpp - machine files: TOML -> MachineSpec, every key checked
// (docs/vboard-machine.md).  Errors say file:line, the key and why; an
// unknown key is an error (a typo must not silently fall back to a
// default).
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "machine.h"
#include "toml.h"

namespace vb::plant {

namespace {

using toml::Value;

// One table being read: typed getters that remember which keys were used.
class Table {
  public:
    Table(const Value &v, std::string path, const std::string &file, std::string &err)
        : v_(v), path_(std::move(path)), file_(file), err_(err)
    {
    }

    bool has(const char *key) const { return v_.find(key) != nullptr; }
    int line() const { return v_.line; }
    std::string key(const char *k) const { return path_.empty() ? k : path_ + "." + k; }

    bool fail(const Value *v, const std::string &key, const std::string &why)
    {
        err_ = file_ + ":" + std::to_string(v ? v->line : v_.line) + ": " + key + ": " + why;
        return false;
    }

    const Value *get(const char *k)
    {
        used_.insert(k);
        return v_.find(k);
    }

    bool number(const char *k, double &out, double lo, double hi, bool required = false,
                bool lo_open = false)
    {
        const Value *v = get(k);
        if (!v)
            return !required || fail(nullptr, key(k), "missing (required)");
        if (!v->is_number())
            return fail(v, key(k), std::string("must be a number, not ") + toml::type_name(v->type));
        double x = v->as_double();
        if (!std::isfinite(x) || x < lo || x > hi || (lo_open && x == lo)) {
            std::ostringstream os;
            os << "value " << x << " is out of range: must be " << (lo_open ? "> " : ">= ") << lo;
            if (std::isfinite(hi))
                os << " and <= " << hi;
            return fail(v, key(k), os.str());
        }
        out = x;
        return true;
    }

    bool integer(const char *k, int64_t &out, int64_t lo, int64_t hi, bool required = false)
    {
        const Value *v = get(k);
        if (!v)
            return !required || fail(nullptr, key(k), "missing (required)");
        if (v->type != Value::Type::Integer)
            return fail(v, key(k), std::string("must be an integer, not ") + toml::type_name(v->type));
        if (v->integer < lo || v->integer > hi)
            return fail(v, key(k), "value " + std::to_string(v->integer) + " is out of range " +
                                       std::to_string(lo) + ".." + std::to_string(hi));
        out = v->integer;
        return true;
    }

    bool boolean(const char *k, bool &out)
    {
        const Value *v = get(k);
        if (!v)
            return true;
        if (v->type != Value::Type::Bool)
            return fail(v, key(k), std::string("must be true or false, not ") + toml::type_name(v->type));
        out = v->boolean;
        return true;
    }

    bool string(const char *k, std::string &out, std::initializer_list<const char *> choices,
                bool required = false)
    {
        const Value *v = get(k);
        if (!v)
            return !required || fail(nullptr, key(k), "missing (required)");
        if (v->type != Value::Type::String)
            return fail(v, key(k), std::string("must be a string, not ") + toml::type_name(v->type));
        if (choices.size()) {
            std::string list;
            for (const char *c : choices) {
                if (v->str == c) {
                    out = v->str;
                    return true;
                }
                list += std::string(list.empty() ? "" : ", ") + "\"" + c + "\"";
            }
            return fail(v, key(k), "\"" + v->str + "\" is not one of " + list);
        }
        out = v->str;
        return true;
    }

    // Every key was read: anything else is a typo or a misplaced key.
    bool no_unknown_keys()
    {
        for (const auto &kv : v_.table)
            if (!used_.count(kv.first)) {
                std::string known;
                for (const std::string &u : used_)
                    known += (known.empty() ? "" : ", ") + u;
                return fail(&kv.second, key(kv.first.c_str()),
                            "unknown key (this table knows: " + known + ")");
            }
        return true;
    }

    const std::string &path() const { return path_; }
    const std::string &file() const { return file_; }
    std::string &err() { return err_; }

  private:
    const Value &v_;
    std::string path_;
    const std::string &file_;
    std::string &err_;
    std::set<std::string> used_;
};

struct Ctx {
    std::vector<std::pair<std::string, std::string>> names;
    uint32_t io_pins;
    std::string board, firmware;
    std::set<int> outputs; // pins the machine drives (each only once)
};

// A pin: an I/O number, "IO n", a connector label ("P2-05") or a module
// function of the firmware ("Encoder 0 A", Pluto "QA0").
bool resolve_pin(Table &t, const Value *v, const std::string &key, Ctx &c, int &pin)
{
    if (v->type == Value::Type::Integer) {
        if (v->integer < 0 || v->integer >= c.io_pins)
            return t.fail(v, key, "I/O pin " + std::to_string(v->integer) +
                                      " does not exist (board " + c.board + " has pins 0.." +
                                      std::to_string(c.io_pins - 1) + ")");
        pin = static_cast<int>(v->integer);
        return true;
    }
    if (v->type != Value::Type::String)
        return t.fail(v, key, "a pin is an I/O number or a pin name, not " +
                                  std::string(toml::type_name(v->type)));
    const std::string &s = v->str;
    if (s.compare(0, 3, "IO ") == 0) {
        char *end = nullptr;
        long n = std::strtol(s.c_str() + 3, &end, 10);
        if (*end || s.size() == 3 || n < 0 || n >= static_cast<long>(c.io_pins))
            return t.fail(v, key, "\"" + s + "\" is not an I/O pin of board " + c.board +
                                      " (0.." + std::to_string(c.io_pins - 1) + ")");
        pin = static_cast<int>(n);
        return true;
    }
    for (size_t i = 0; i < c.names.size(); i++)
        if (s == c.names[i].first || s == c.names[i].second) {
            pin = static_cast<int>(i);
            return true;
        }
    if (c.names.empty())
        return t.fail(v, key, "pin \"" + s + "\": names need the firmware's pin map; firmware \"" +
                                  c.firmware + "\" is not known for board " + c.board +
                                  " (use an I/O number)");
    return t.fail(v, key, "no pin \"" + s + "\" on board " + c.board + " with firmware " +
                              c.firmware + " (see its .PIN file: connector labels like \"" +
                              (c.names[0].first.empty() ? c.names[0].second : c.names[0].first) +
                              "\" or module pins like \"Encoder 0 A\")");
}

// A pin the firmware reads, that the machine drives: once only.
bool output_pin(Table &t, const Value *v, const std::string &key, Ctx &c, int pin)
{
    if (!c.outputs.insert(pin).second)
        return t.fail(v, key, "I/O pin " + std::to_string(pin) +
                                  " is already driven by another part of the machine");
    return true;
}

bool level(Table &t, const char *k, bool &high)
{
    std::string s = high ? "high" : "low";
    if (!t.string(k, s, {"high", "low"}))
        return false;
    high = s == "high";
    return true;
}

// A signal: a pin, or { pin = ..., active = "high"|"low", ... } (extra
// keys read by the caller through `sub`).
bool signal(Table &t, const char *k, Ctx &c, PinRef &ref, bool drives, bool default_high,
            bool required = false)
{
    const Value *v = t.get(k);
    if (!v)
        return !required || t.fail(nullptr, t.key(k), "missing (required)");
    ref.active_high = default_high;
    if (v->type == Value::Type::Table) {
        Table s(*v, t.key(k), t.file(), t.err());
        const Value *p = s.get("pin");
        if (!p)
            return s.fail(v, s.key("pin"), "missing (required)");
        if (!resolve_pin(s, p, s.key("pin"), c, ref.pin) || !level(s, "active", ref.active_high) ||
            !s.no_unknown_keys())
            return false;
        return !drives || output_pin(s, p, s.key("pin"), c, ref.pin);
    }
    if (!resolve_pin(t, v, t.key(k), c, ref.pin))
        return false;
    return !drives || output_pin(t, v, t.key(k), c, ref.pin);
}

bool encoder(Table &parent, const char *k, Ctx &c, EncoderSpec &e, bool scale, bool rotary,
             uint64_t &seed)
{
    const Value *v = parent.get(k);
    if (!v)
        return true;
    if (v->type != Value::Type::Table)
        return parent.fail(v, parent.key(k), "must be a table");
    Table t(*v, parent.key(k), parent.file(), parent.err());
    e.present = true;
    if (!signal(t, "a", c, e.a, true, true, true) || !signal(t, "b", c, e.b, true, true, true) ||
        !signal(t, "index", c, e.index, true, true))
        return false;
    // an encoder on the motor counts per motor revolution; a scale per mm
    // of the slide, or per revolution of a spindle
    bool per_mm = scale && !rotary;
    double cpu = 0;
    if (!t.number(per_mm ? "counts_per_mm" : "counts_per_rev", cpu, 0, 1e9, true, true))
        return false;
    e.counts_per_unit = cpu;
    int64_t idx = 0;
    if (!t.integer("index_count", idx, 0, INT64_MAX))
        return false;
    double irev = 0;
    if (per_mm) {
        double every = 0;
        if (!t.number("index_every_mm", every, 0, 1e9))
            return false;
        irev = every * cpu;
    } else {
        irev = cpu;
    }
    if (e.index.used() && (irev < 1 || std::fabs(irev - std::round(irev)) > 1e-9))
        return t.fail(v, t.key(per_mm ? "index_every_mm" : "counts_per_rev"),
                      "the index needs a whole number of counts per period (got " +
                          std::to_string(irev) + ")");
    e.enc.counts_per_rev = e.index.used() ? static_cast<int64_t>(std::llround(irev)) : 0;
    e.enc.index_count = idx;
    double gns = 0;
    if (!t.boolean("reverse", e.enc.reverse) ||
        !t.number("glitch_rate_hz", e.enc.glitch_rate, 0, 1e7) ||
        !t.number("glitch_ns", gns, 0, 1e6) || !t.number("jitter_counts", e.enc.jitter, 0, 1e3))
        return false;
    e.enc.glitch_ns = static_cast<uint64_t>(gns);
    if (e.enc.glitch_rate > 0 && e.enc.glitch_ns == 0)
        return t.fail(v, t.key("glitch_ns"), "glitch_rate_hz > 0 needs glitch_ns > 0");
    e.enc.seed = seed++;
    return t.no_unknown_keys();
}

bool switches(Table &t, Ctx &c, AxisSpec &a)
{
    for (const char *name : {"limit_min", "limit_max", "home"}) {
        const Value *v = t.get(name);
        if (!v)
            continue;
        if (v->type != Value::Type::Table)
            return t.fail(v, t.key(name), "must be a table { pin = ..., ... }");
        Table s(*v, t.key(name), t.file(), t.err());
        SwitchSpec w;
        w.name = name;
        w.pin.active_high = true;
        const Value *p = s.get("pin");
        if (!p)
            return s.fail(v, s.key("pin"), "missing (required)");
        if (!resolve_pin(s, p, s.key("pin"), c, w.pin.pin) ||
            !output_pin(s, p, s.key("pin"), c, w.pin.pin) || !level(s, "active", w.pin.active_high))
            return false;
        const char *unit = a.rotary ? "_rev" : "_mm";
        std::string at = std::string("at") + unit, from = std::string("from") + unit,
                    to = std::string("to") + unit;
        double x = 0;
        if (std::string(name) == "home") {
            w.from = -kInf;
            w.to = kInf;
            if (!s.number(from.c_str(), w.from, -1e9, 1e9, true) ||
                !s.number(to.c_str(), w.to, -1e9, 1e9, true))
                return false;
            if (w.to < w.from)
                return s.fail(v, s.key(to.c_str()), "must not be below " + from);
        } else {
            if (!s.number(at.c_str(), x, -1e9, 1e9, true))
                return false;
            if (std::string(name) == "limit_min") {
                w.from = -kInf;
                w.to = x;
            } else {
                w.from = x;
                w.to = kInf;
            }
        }
        if (!s.no_unknown_keys())
            return false;
        a.switches.push_back(w);
    }
    return true;
}

// The load the slide (or spindle) puts on the motor shaft.
struct Load {
    double inertia = 0, viscous = 0, coulomb = 0, torque = 0;
};

bool mechanics(Table &t, AxisSpec &a, Load &l)
{
    double lead_m = a.lead * 1e-3;
    // One radian of the motor moves the slide r metres (or the spindle 1/gear rad).
    double r = a.rotary ? 1.0 / a.gear : lead_m / (2 * M_PI * a.gear);
    if (a.rotary) {
        double j = 0, f = 0, b = 0, tq = 0;
        if (!t.number("load_inertia_kg_m2", j, 0, 1e3) || !t.number("friction_nm", f, 0, 1e4) ||
            !t.number("viscous_nm_s_per_rad", b, 0, 1e4) || !t.number("load_torque_nm", tq, -1e4, 1e4))
            return false;
        l.inertia = j * r * r;
        l.coulomb = f * r;
        l.viscous = b * r * r;
        l.torque = tq * r;
        return true;
    }
    double m = 0, js = 0, f = 0, c = 0, g = 0;
    if (!t.number("mass_kg", m, 0, 1e5) || !t.number("screw_inertia_kg_m2", js, 0, 1e3) ||
        !t.number("friction_n", f, 0, 1e6) || !t.number("viscous_n_s_per_m", c, 0, 1e7) ||
        !t.number("gravity_n", g, -1e6, 1e6))
        return false;
    l.inertia = m * r * r + js / (a.gear * a.gear);
    l.coulomb = f * r;
    l.viscous = c * r * r;
    l.torque = g * r;
    return true;
}

bool dc_motor(Table &t, Ctx &c, AxisSpec &a, const Load &l)
{
    (void)c;
    DcMotorParams &p = a.dc;
    double j = 0, b = 0, f = 0;
    if (!t.number("resistance_ohm", p.resistance, 0, 1e4, true, true) ||
        !t.number("inductance_h", p.inductance, 0, 10, true, true) ||
        !t.number("kt_nm_per_a", p.kt, 0, 100, true, true) ||
        !t.number("ke_v_s_per_rad", p.ke, 0, 100, true, true) ||
        !t.number("inertia_kg_m2", j, 0, 100, true, true) ||
        !t.number("viscous_nm_s_per_rad", b, 0, 100) || !t.number("friction_nm", f, 0, 1e3))
        return false;
    p.shaft.inertia = j + l.inertia;
    p.shaft.viscous = b + l.viscous;
    p.shaft.coulomb = f + l.coulomb;
    p.shaft.load = l.torque;
    return t.no_unknown_keys();
}

bool stepper_motor(Table &t, AxisSpec &a, const Load &l)
{
    StepperParams &p = a.stepper;
    int64_t fs = 200;
    double j = 0, b = 0, f = 0, d = 0;
    if (!t.integer("full_steps", fs, 4, 100000) || !t.number("inertia_kg_m2", j, 0, 100, true, true) ||
        !t.number("viscous_nm_s_per_rad", b, 0, 100) || !t.number("friction_nm", f, 0, 1e3) ||
        !t.number("damping_nm_s_per_rad", d, 0, 100))
        return false;
    if (fs % 4)
        return t.fail(t.get("full_steps"), t.key("full_steps"),
                      "must be a multiple of 4 (a two-phase motor: 4 full steps per tooth)");
    p.full_steps = static_cast<int>(fs);
    const Value *cv = t.get("torque_curve");
    if (!cv)
        return t.fail(nullptr, t.key("torque_curve"),
                      "missing (required): [[rpm, N m], ...] pull-out torque points");
    if (cv->type != Value::Type::Array || cv->array.empty())
        return t.fail(cv, t.key("torque_curve"), "must be a non-empty array of [rpm, N m] pairs");
    p.curve.clear();
    for (size_t i = 0; i < cv->array.size(); i++) {
        const Value &e = cv->array[i];
        std::string k = t.key("torque_curve") + "[" + std::to_string(i) + "]";
        if (e.type != Value::Type::Array || e.array.size() != 2 || !e.array[0].is_number() ||
            !e.array[1].is_number())
            return t.fail(&e, k, "must be a pair [rpm, N m]");
        double rpm = e.array[0].as_double(), nm = e.array[1].as_double();
        if (!(rpm >= 0) || !(nm >= 0) || !std::isfinite(rpm) || !std::isfinite(nm))
            return t.fail(&e, k, "speed and torque must be finite and >= 0");
        double w = rpm * 2 * M_PI / 60;
        if (!p.curve.empty() && w <= p.curve.back().first)
            return t.fail(&e, k, "speeds must rise from point to point");
        p.curve.emplace_back(w, nm);
    }
    p.damping = d;
    p.shaft.inertia = j + l.inertia;
    p.shaft.viscous = b + l.viscous;
    p.shaft.coulomb = f + l.coulomb;
    p.shaft.load = l.torque;
    return t.no_unknown_keys();
}

bool amplifier(Table &t, Ctx &c, AxisSpec &a)
{
    std::string in = "pwm_dir";
    bool neg_high = true;
    if (!t.string("input", in, {"pwm_dir", "up_down"}) ||
        !t.number("bus_v", a.bus_volts, 0, 1e4, true, true) ||
        !signal(t, "a", c, a.in_a, false, true, true) || !signal(t, "b", c, a.in_b, false, true, true) ||
        !level(t, "negative", neg_high) || !signal(t, "enable", c, a.enable, false, true) ||
        !t.number("current_limit_a", a.dc.current_limit, 0, 1e5, false, true) ||
        !t.number("voltage_limit_v", a.dc.voltage_limit, 0, 1e4, false, true))
        return false;
    a.bridge = in == "pwm_dir" ? BridgeInput::Mode::PwmDir : BridgeInput::Mode::UpDown;
    a.negative_level = neg_high;
    const Value *fv = t.get("fault");
    if (fv) {
        if (fv->type != Value::Type::Table)
            return t.fail(fv, t.key("fault"), "must be a table { pin = ..., after_ms = ... }");
        Table f(*fv, t.key("fault"), t.file(), t.err());
        const Value *p = f.get("pin");
        double ms = 0;
        a.fault.active_high = true;
        if (!p)
            return f.fail(fv, f.key("pin"), "missing (required)");
        if (!resolve_pin(f, p, f.key("pin"), c, a.fault.pin) ||
            !output_pin(f, p, f.key("pin"), c, a.fault.pin) ||
            !level(f, "active", a.fault.active_high) || !f.number("after_ms", ms, 0, 1e6, true, true) ||
            !f.no_unknown_keys())
            return false;
        if (!std::isfinite(a.dc.current_limit))
            return f.fail(fv, f.key("after_ms"), "the fault trips on the current limit: set current_limit_a");
        a.fault_after_ns = static_cast<uint64_t>(ms * 1e6);
    }
    return t.no_unknown_keys();
}

bool drive(Table &t, Ctx &c, AxisSpec &a)
{
    std::string model, in = "step_dir";
    bool neg_high = true;
    int64_t ms = 1;
    if (!t.string("model", model, {"G201", "G202", "G203V", "generic"}, true) ||
        !t.integer("microsteps", ms, 1, 256) || !t.string("input", in, {"step_dir", "quadrature"}))
        return false;
    drive_timing(model, a.timing);
    a.drive_model = model;
    a.microsteps = static_cast<int>(ms);
    a.step_mode = in == "step_dir" ? StepInput::Mode::StepDir : StepInput::Mode::Quadrature;
    std::string edge = a.timing.rising ? "rising" : "falling";
    double hi = static_cast<double>(a.timing.min_high), lo = static_cast<double>(a.timing.min_low),
           su = static_cast<double>(a.timing.dir_setup), ho = static_cast<double>(a.timing.dir_hold);
    if (!t.string("step_edge", edge, {"rising", "falling"}) || !t.number("min_high_ns", hi, 0, 1e9) ||
        !t.number("min_low_ns", lo, 0, 1e9) || !t.number("dir_setup_ns", su, 0, 1e9) ||
        !t.number("dir_hold_ns", ho, 0, 1e9))
        return false;
    a.timing = StepTiming{edge == "rising", static_cast<uint64_t>(hi), static_cast<uint64_t>(lo),
                          static_cast<uint64_t>(su), static_cast<uint64_t>(ho)};
    bool quad = a.step_mode == StepInput::Mode::Quadrature;
    if (!signal(t, quad ? "a" : "step", c, a.in_a, false, true, true) ||
        !signal(t, quad ? "b" : "dir", c, a.in_b, false, true, true) ||
        !signal(t, "enable", c, a.enable, false, true))
        return false;
    if (quad) {
        bool rev = false;
        if (!t.boolean("reverse", rev))
            return false;
        a.negative_level = rev;
    } else if (!level(t, "negative", neg_high)) {
        return false;
    } else {
        a.negative_level = neg_high;
    }
    return t.no_unknown_keys();
}

bool axis(const Value &v, size_t i, Ctx &c, const std::string &file, std::string &err,
          uint64_t &seed, AxisSpec &a)
{
    Table t(v, "axis[" + std::to_string(i) + "]", file, err);
    std::string type = "linear";
    if (!t.string("name", a.name, {}, true) || !t.string("type", type, {"linear", "rotary"}))
        return false;
    if (a.name.empty() || a.name.find_first_of(" ,\"") != std::string::npos)
        return t.fail(t.get("name"), t.key("name"), "must be a non-empty word (no spaces, commas, quotes)");
    a.rotary = type == "rotary";
    const char *u = a.rotary ? "_rev" : "_mm";
    if ((!a.rotary && !t.number("lead_mm", a.lead, 0, 1e4, true, true)) ||
        !t.number("gear", a.gear, 0, 1e4, false, true) ||
        !t.number((std::string("position") + u).c_str(), a.start, -1e9, 1e9))
        return false;
    Load load;
    if (!mechanics(t, a, load))
        return false;
    const Value *hs = t.get((std::string("hard_stops") + u).c_str());
    if (hs) {
        std::string k = t.key((std::string("hard_stops") + u).c_str());
        if (hs->type != Value::Type::Array || hs->array.size() != 2 || !hs->array[0].is_number() ||
            !hs->array[1].is_number() || !(hs->array[0].as_double() < hs->array[1].as_double()))
            return t.fail(hs, k, "must be [min, max] with min < max");
        a.stops = true;
        a.stop_min = hs->array[0].as_double();
        a.stop_max = hs->array[1].as_double();
        if (a.start < a.stop_min || a.start > a.stop_max)
            return t.fail(hs, k, "the axis starts outside its hard stops");
    }
    if (!switches(t, c, a))
        return false;
    const Value *mv = t.get("motor");
    if (!mv || mv->type != Value::Type::Table)
        return t.fail(mv, t.key("motor"), mv ? "must be a table" : "missing (required): [axis.motor]");
    Table m(*mv, t.key("motor"), file, err);
    std::string mt;
    if (!m.string("type", mt, {"dc", "stepper"}, true))
        return false;
    a.motor = mt == "dc" ? AxisSpec::Motor::Dc : AxisSpec::Motor::Stepper;
    if (a.motor == AxisSpec::Motor::Dc) {
        if (!dc_motor(m, c, a, load))
            return false;
        const Value *av = t.get("amplifier");
        if (!av || av->type != Value::Type::Table)
            return t.fail(av, t.key("amplifier"),
                          av ? "must be a table" : "missing (required for a dc motor): [axis.amplifier]");
        Table at(*av, t.key("amplifier"), file, err);
        if (!amplifier(at, c, a))
            return false;
        if (t.has("drive"))
            return t.fail(t.get("drive"), t.key("drive"), "a dc motor has an [axis.amplifier], not a drive");
    } else {
        if (!stepper_motor(m, a, load))
            return false;
        const Value *dv = t.get("drive");
        if (!dv || dv->type != Value::Type::Table)
            return t.fail(dv, t.key("drive"),
                          dv ? "must be a table" : "missing (required for a stepper): [axis.drive]");
        Table dt(*dv, t.key("drive"), file, err);
        if (!drive(dt, c, a))
            return false;
        if (t.has("amplifier"))
            return t.fail(t.get("amplifier"), t.key("amplifier"), "a stepper has a [axis.drive], not an amplifier");
    }
    if (!encoder(t, "encoder", c, a.encoder, false, a.rotary, seed) ||
        !encoder(t, "scale", c, a.scale, true, a.rotary, seed))
        return false;
    return t.no_unknown_keys();
}

} // namespace

bool parse_machine(const std::string &text, const std::string &path, const std::string &board,
                   const PinNamesFn &names, uint32_t io_pins, MachineSpec &spec, std::string &err)
{
    Value root;
    if (!toml::parse(text, path, root, err))
        return false;
    MachineSpec s;
    s.path = path;
    Table t(root, "", path, err);
    if (!t.string("board", s.board, {}, true) || !t.string("firmware", s.firmware, {}))
        return false;
    if (s.board != board)
        return t.fail(t.get("board"), "board",
                      "the file is for board " + s.board + ", this board is a " + board);
    int64_t step = 1000, seed = 1;
    if (!t.integer("step_ns", step, 10, 1000000) || !t.integer("seed", seed, 0, INT64_MAX))
        return false;
    s.step_ns = static_cast<uint64_t>(step);
    Ctx c{s.firmware.empty() ? std::vector<std::pair<std::string, std::string>>{} : names(s.firmware),
          io_pins, board, s.firmware, {}};
    if (s.firmware.empty())
        c.firmware = "(none)";
    else if (c.names.empty())
        return t.fail(t.get("firmware"), "firmware",
                      "firmware \"" + s.firmware + "\" is not built for board " + board);
    const Value *axes = t.get("axis");
    if (!axes || axes->type != Value::Type::Array || !axes->array_of_tables || axes->array.empty())
        return t.fail(axes, "axis", "the machine needs at least one [[axis]] table");
    uint64_t useed = static_cast<uint64_t>(seed) * 1000003u + 1;
    std::set<std::string> seen;
    for (size_t i = 0; i < axes->array.size(); i++) {
        AxisSpec a;
        if (!axis(axes->array[i], i, c, path, err, useed, a))
            return false;
        if (!seen.insert(a.name).second)
            return t.fail(&axes->array[i], "axis[" + std::to_string(i) + "].name",
                          "axis name \"" + a.name + "\" is used twice");
        s.axes.push_back(a);
    }
    if (!t.no_unknown_keys())
        return false;
    spec = std::move(s);
    return true;
}

bool load_machine(const std::string &path, const std::string &board,
                  const PinNamesFn &names, uint32_t io_pins,
                  MachineSpec &spec, std::string &err)
{
    std::ifstream in(path);
    if (!in) {
        err = "cannot read machine file " + path;
        return false;
    }
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_machine(ss.str(), path, board, names, io_pins, spec, err);
}

} // namespace vb::plant
