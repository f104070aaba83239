// SPDX-License-Identifier: GPL-2.0-or-later
//
// Machine files: a good file and what it sets (including the load referred
// to the motor: m (lead / 2 pi gear)^2 ...), the TOML subset, and every
// kind of bad input with its file:line and key in the message.
#include <string>
#include <vector>

#include "machine.h"
#include "plant_test.h"
#include "toml.h"

using namespace vb::plant;

namespace plant_test {
namespace {

std::vector<std::pair<std::string, std::string>> fake_names(const std::string &fw)
{
    if (fw != "FW1")
        return {};
    std::vector<std::pair<std::string, std::string>> v;
    for (int i = 0; i < 24; i++)
        v.emplace_back("P2-" + std::to_string(i * 2 + 1), "");
    v[0].second = "Encoder 0 A";
    v[1].second = "Encoder 0 B";
    v[2].second = "Encoder 0 Index";
    v[3].second = "PWMGen 0 Out0";
    v[4].second = "PWMGen 0 Out1";
    v[5].second = "PWMGen 0 NotEnable";
    return v;
}

const char *kGood = R"(# a test machine
board = "b1"
firmware = "FW1"
step_ns = 500

[[axis]]
name = "x"
lead_mm = 5
gear = 2
mass_kg = 40
friction_n = 30
viscous_n_s_per_m = 100
gravity_n = -392.4
position_mm = 10
hard_stops_mm = [-5, 305]
limit_min = { pin = "P2-15", at_mm = -2, active = "low" }
limit_max = { pin = 8, at_mm = 302 }
home = { pin = "IO 9", from_mm = 150, to_mm = 400 }

[axis.motor]
type = "dc"
resistance_ohm = 1.2
inductance_h = 2.5e-3
kt_nm_per_a = 0.08
ke_v_s_per_rad = 0.08
inertia_kg_m2 = 1.5e-4
friction_nm = 0.01

[axis.amplifier]
input = "pwm_dir"
a = "PWMGen 0 Out0"
b = "PWMGen 0 Out1"
negative = "high"
bus_v = 48
current_limit_a = 12
enable = { pin = "PWMGen 0 NotEnable", active = "low" }
fault = { pin = 10, active = "low", after_ms = 50 }

[axis.encoder]
a = "Encoder 0 A"
b = "Encoder 0 B"
index = "Encoder 0 Index"
counts_per_rev = 2000

[[axis]]
name = "z"
lead_mm = 5
[axis.motor]
type = "stepper"
full_steps = 200
inertia_kg_m2 = 4.8e-5
torque_curve = [
  [0, 2.0],   # rpm, N m
  [600, 1.5],
  [1200, 0.8],
]
[axis.drive]
model = "G203V"
microsteps = 10
step = 11
dir = 12
dir_hold_ns = 500
)";

bool parse(const std::string &text, MachineSpec &s, std::string &err)
{
    return parse_machine(text, "m.toml", "b1", fake_names, 24, s, err);
}

void good_file()
{
    MachineSpec s;
    std::string err;
    bool ok = parse(kGood, s, err);
    CHECK(ok);
    if (!ok) {
        std::fprintf(stderr, "%s\n", err.c_str());
        return;
    }
    CHECK(s.step_ns == 500 && s.axes.size() == 2);
    const AxisSpec &x = s.axes[0];
    CHECK(x.name == "x" && !x.rotary && x.motor == AxisSpec::Motor::Dc);
    double r = 5e-3 / (2 * M_PI * 2);
    CHECK_REL(x.dc.shaft.inertia, 1.5e-4 + 40 * r * r, 1e-15);
    CHECK_REL(x.dc.shaft.coulomb, 0.01 + 30 * r, 1e-15);
    CHECK_REL(x.dc.shaft.viscous, 100 * r * r, 1e-15);
    CHECK_REL(x.dc.shaft.load, -392.4 * r, 1e-15);
    CHECK(x.in_a.pin == 3 && x.in_b.pin == 4 && x.enable.pin == 5 && !x.enable.active_high);
    CHECK(x.fault.pin == 10 && x.fault_after_ns == 50000000);
    CHECK(x.encoder.present && x.encoder.a.pin == 0 && x.encoder.index.pin == 2 &&
          x.encoder.enc.counts_per_rev == 2000);
    CHECK(x.switches.size() == 3 && x.switches[0].pin.pin == 7 && !x.switches[0].pin.active_high &&
          x.switches[1].pin.pin == 8 && x.switches[2].pin.pin == 9 && x.switches[2].from == 150);
    CHECK(x.stops && x.stop_min == -5 && x.stop_max == 305 && x.start == 10);
    const AxisSpec &z = s.axes[1];
    CHECK(z.motor == AxisSpec::Motor::Stepper && z.microsteps == 10 && z.drive_model == "G203V");
    CHECK(z.timing.rising && z.timing.min_high == 1000 && z.timing.dir_hold == 500);
    CHECK(z.stepper.curve.size() == 3);
    CHECK_REL(z.stepper.curve[1].first, 600 * 2 * M_PI / 60, 1e-15);
}

// Replace the first occurrence of `from` in the good file.
std::string edit(const std::string &from, const std::string &to)
{
    std::string s = kGood;
    size_t at = s.find(from);
    CHECK(at != std::string::npos);
    if (at != std::string::npos)
        s.replace(at, from.size(), to);
    return s;
}

void bad(const std::string &text, const std::string &want)
{
    MachineSpec s;
    s.step_ns = 4242;
    std::string err;
    CHECK(!parse(text, s, err));
    CHECK_CONTAINS(err, want);
    CHECK(s.step_ns == 4242); // nothing applied
}

void bad_files()
{
    bad(edit("lead_mm = 5\ngear", "lead_mm = 5\nlead_mm = 6\ngear"),
        "m.toml:9: key 'lead_mm' is defined twice (first on line 8)");
    bad(edit("gear = 2", "gears = 2"), "m.toml:9: axis[0].gears: unknown key");
    bad(edit("mass_kg = 40", "mass_kg = \"40\""), "m.toml:10: axis[0].mass_kg: must be a number");
    bad(edit("mass_kg = 40", "mass_kg = -1"), "m.toml:10: axis[0].mass_kg: value -1 is out of range");
    bad(edit("resistance_ohm = 1.2", "resistance_ohm = 0"),
        "axis[0].motor.resistance_ohm: value 0 is out of range: must be > 0");
    bad(edit("inductance_h = 2.5e-3\n", ""), "axis[0].motor.inductance_h: missing (required)");
    bad(edit("a = \"PWMGen 0 Out0\"", "a = \"PWMGen 9 Out0\""),
        "m.toml:31: axis[0].amplifier.a: no pin \"PWMGen 9 Out0\" on board b1 with firmware FW1");
    bad(edit("limit_max = { pin = 8,", "limit_max = { pin = 99,"),
        "m.toml:17: axis[0].limit_max.pin: I/O pin 99 does not exist (board b1 has pins 0..23)");
    bad(edit("limit_max = { pin = 8,", "limit_max = { pin = 0,"),
        "axis[0].encoder.a: I/O pin 0 is already driven by another part of the machine");
    bad(edit("type = \"dc\"", "type = \"ac\""),
        "m.toml:21: axis[0].motor.type: \"ac\" is not one of \"dc\", \"stepper\"");
    bad(edit("model = \"G203V\"", "model = \"G2\""), "axis[1].drive.model: \"G2\" is not one of");
    bad(edit("[1200, 0.8],", "[500, 0.8],"),
        "m.toml:55: axis[1].motor.torque_curve[2]: speeds must rise from point to point");
    bad(edit("board = \"b1\"", "board = \"b2\""),
        "m.toml:2: board: the file is for board b2, this board is a b1");
    bad(edit("firmware = \"FW1\"", "firmware = \"FW2\""),
        "m.toml:3: firmware: firmware \"FW2\" is not built for board b1");
    bad(edit("hard_stops_mm = [-5, 305]", "hard_stops_mm = [305, -5]"),
        "axis[0].hard_stops_mm: must be [min, max] with min < max");
    bad(edit("position_mm = 10", "position_mm = 400"), "the axis starts outside its hard stops");
    bad(edit("[0, 2.0],", "[0, 2.0"), "expected ',' or ']' in the array opened on line");
    bad(edit("step_ns = 500", "step_ns = 5"), "m.toml:4: step_ns: value 5 is out of range 10..1000000");
    bad(edit("name = \"z\"", "name = \"x\""), "axis[1].name: axis name \"x\" is used twice");
    bad(edit("name = \"z\"", "name = \"z z\""), "axis[1].name: must be a non-empty word");
    bad(edit("[axis.drive]", "[axis.amplifier]"), "axis[1].drive: missing (required for a stepper)");
    bad(edit("counts_per_rev = 2000", "counts_per_rev = 2000.5"),
        "the index needs a whole number of counts per period");
    bad(edit("current_limit_a = 12\n", ""), "the fault trips on the current limit");
    bad(std::string(kGood) + "seed = 1\n", "m.toml:63: axis[1].drive.seed: unknown key");
    bad("board = \"b1\"\n", "m.toml:1: axis: the machine needs at least one [[axis]] table");
    bad("board = \"b1\"\nstarted = 1979-05-27\n", "m.toml:2: '1979-05-27': dates and times are not supported");
    bad("board = \"\"\"b1\"\"\"\n", "m.toml:1: multi-line strings are not supported");
    bad("board = \"b1\n", "m.toml:1: string is not closed on its line");
    bad("board b1\n", "m.toml:1: expected '=' after key 'board'");
    bad("[axis\n", "m.toml:1: table header [axis is not closed by ']'");
    bad("board = \"b1\" x\n", "m.toml:1: unexpected 'x' after the value");
    bad("a = 1\n[a]\n", "m.toml:2: [a]: the key is already an integer (line 1)");
    bad("[t]\n[t]\n", "m.toml:2: table [t] is defined twice (first on line 1)");
    bad("a = 01\n", "m.toml:1: '01': integers have no leading zeros");
    bad("a = 1__0\n", "m.toml:1: '1__0' is not a number (misplaced '_')");
    bad("a = yes\n", "m.toml:1: 'yes' is not a value (strings need quotes)");
    bad("a = \"\\q\"\n", "m.toml:1: unknown escape '\\q' in a string");
}

void toml_values()
{
    toml::Value v;
    std::string err;
    bool ok = toml::parse("a.b = 0x1F\n'c d' = -1_000\n[e]\nf = [1, 2.5, 'x', true, inf, { g = 1 }]\n"
                          "[[h]]\ni = 1\n[[h]]\ni = 2\n[h.j]\nk = +3e2 # c\n",
                          "t.toml", v, err);
    CHECK(ok);
    if (!ok) {
        std::fprintf(stderr, "%s\n", err.c_str());
        return;
    }
    CHECK(v.find("a")->find("b")->integer == 31);
    CHECK(v.find("c d")->integer == -1000);
    const toml::Value *f = v.find("e")->find("f");
    CHECK(f->array.size() == 6 && f->array[1].number == 2.5 && f->array[2].str == "x" &&
          f->array[3].boolean && std::isinf(f->array[4].number) &&
          f->array[5].find("g")->integer == 1 && f->line == 4);
    const toml::Value *h = v.find("h");
    CHECK(h->array.size() == 2 && h->array[1].find("i")->integer == 2 &&
          h->array[1].find("j")->find("k")->number == 300 && h->array[1].find("j")->line == 9);
}

} // namespace

void config()
{
    good_file();
    bad_files();
    toml_values();
}

} // namespace plant_test
