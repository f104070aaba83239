// SPDX-License-Identifier: GPL-2.0-or-later
//
// r7i76.cpp - a virtual 7I76 behind a Smart Serial channel: 32 field
// inputs, 16 field outputs, the spindle interface (analog output 0..10 V,
// enable, direction), four analog inputs and the field-voltage monitor.
//
// Process data (docs/sserial.md, "7I76 process data"), bit 0 = bit 0 of the
// first byte:
//   host -> 7I76 (48 bits): 0..15 outputs 0..15, 16 spindle enable,
//       17 spindle direction, 32..47 spindle DAC (0..65535 = 0..10 V)
//   7I76 -> host: 0..31 inputs 0..31; modes 1 and 2 add four 12-bit analog
//       inputs at 32, 44, 56, 68 (LSB 0.01 V); mode 2 adds the field
//       voltage at 80 (12 bits, LSB 0.01 V).  Sizes: 32 / 80 / 92 bits.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "link.h"

namespace vb::sserial {

namespace {

constexpr double kAdcLsbV = 0.01;
constexpr uint32_t kAdcMax = 4095;
constexpr double kDacFullV = 10.0;

uint32_t adc(double v)
{
    double r = std::round(v / kAdcLsbV);
    return r <= 0 ? 0 : r >= kAdcMax ? kAdcMax : static_cast<uint32_t>(r);
}

bool parse_double(const std::string &s, double &v)
{
    char *end = nullptr;
    v = std::strtod(s.c_str(), &end);
    return !s.empty() && *end == '\0' && std::isfinite(v);
}

bool parse_u32(const std::string &s, uint32_t &v)
{
    char *end = nullptr;
    errno = 0;
    unsigned long long x = std::strtoull(s.c_str(), &end, 0);
    if (s.empty() || *end || errno || x > 0xFFFFFFFFull || s[0] == '-')
        return false;
    v = static_cast<uint32_t>(x);
    return true;
}

// The 7I76, and the field I/O channel of a 7I77 (the same process data,
// mode 0 only).
class R7i76 final : public Personality {
  public:
    R7i76(uint32_t unit, bool is_7i77) : unit_(unit), i77_(is_7i77) {}
    std::string type() const override { return i77_ ? "7i77" : "7i76"; }
    std::array<uint8_t, 4> name() const override
    {
        return {'7', 'I', '7', static_cast<uint8_t>(i77_ ? '7' : '6')};
    }
    uint32_t unit() const override { return unit_; }

    bool start(uint8_t mode, uint8_t &in_bits, uint8_t &out_bits) override
    {
        if (mode > (i77_ ? 0 : 2))
            return false;
        mode_ = mode;
        in_bits = mode == 0 ? 32 : mode == 1 ? 80 : 92;
        out_bits = 48;
        return true;
    }

    void process(const std::vector<uint8_t> &out, std::vector<uint8_t> &in,
                 uint8_t &status) override
    {
        outputs_ = get_bits(out, 0, 16);
        spinena_ = get_bits(out, 16, 1) != 0;
        spindir_ = get_bits(out, 17, 1) != 0;
        dac_ = get_bits(out, 32, 16);
        put_bits(in, 0, 32, inputs_);
        if (mode_ >= 1)
            for (unsigned k = 0; k < 4; k++)
                put_bits(in, 32 + 12 * k, 12, adc(analog_[k]));
        if (mode_ == 2)
            put_bits(in, 80, 12, adc(field_));
        status = 0;
    }

    int set(const std::vector<std::string> &a, std::string &err) override
    {
        uint32_t n = 0, v = 0;
        double x = 0;
        if (a.size() == 2 && a[0] == "inputs" && parse_u32(a[1], v)) {
            inputs_ = v;
        } else if (a.size() == 3 && a[0] == "input" && parse_u32(a[1], n) && n < 32 &&
                   parse_u32(a[2], v) && v <= 1) {
            inputs_ = (inputs_ & ~(1u << n)) | (v << n);
        } else if (a.size() == 3 && a[0] == "analog" && parse_u32(a[1], n) && n < 4 &&
                   parse_double(a[2], x)) {
            analog_[n] = x;
        } else if (a.size() == 2 && a[0] == "field" && parse_double(a[1], x)) {
            field_ = x;
        } else {
            err = type() + ": want 'inputs MASK', 'input N 0|1' (N 0..31), 'analog N VOLTS' "
                  "(N 0..3) or 'field VOLTS'";
            return -EINVAL;
        }
        return 0;
    }

    std::string json() const override
    {
        char b[512];
        std::snprintf(b, sizeof b,
                      "\"type\": \"%s\", \"part\": \"io\", \"unit\": %u, \"inputs\": %u, \"outputs\": %u, "
                      "\"spinena\": %s, \"spindir\": %s, \"spinout_raw\": %u, "
                      "\"spinout_v\": %.6f, \"analog_v\": [%.4f, %.4f, %.4f, %.4f], "
                      "\"field_v\": %.4f",
                      type().c_str(), unit_, inputs_, outputs_, spinena_ ? "true" : "false",
                      spindir_ ? "true" : "false", dac_, dac_ * kDacFullV / 65535.0, analog_[0],
                      analog_[1], analog_[2], analog_[3], field_);
        return b;
    }

  private:
    uint32_t unit_;
    bool i77_;
    uint8_t mode_ = 0;
    uint32_t inputs_ = 0, outputs_ = 0, dac_ = 0;
    bool spinena_ = false, spindir_ = false;
    double analog_[4] = {0, 0, 0, 0};
    double field_ = 24.0;
};

} // namespace

std::unique_ptr<Personality> make_7i77_analog(uint32_t unit);

std::unique_ptr<Personality> make_personality(const std::string &type, uint32_t unit)
{
    if (type == "7i76")
        return std::make_unique<R7i76>(unit, false);
    if (type == "7i77")
        return std::make_unique<R7i76>(unit, true);
    if (type == "7i77-analog")
        return make_7i77_analog(unit);
    return nullptr;
}

std::string personality_types()
{
    return "7i76, 7i77 (two channels: field I/O on C, analog servo outputs on C+1)";
}

} // namespace vb::sserial
