// SPDX-License-Identifier: GPL-2.0-or-later
//
// r7i77.cpp - the analog servo channel of a virtual 7I77: six bipolar
// analog outputs (+-10 V) and the analog enable output.  (Its field I/O
// channel is the 7I76 personality in 7I77 dress, r7i76.cpp.)
//
// Process data (docs/sserial.md, "7I77 process data"):
//   host -> 7I77 (91 bits): outputs 0..5 as 15-bit two's complement at
//       0, 15, 30, 45, 60, 75 (+-16383 = +-10 V), 90 analog enable
//   7I77 -> host: nothing (0 bits; the answer is the status byte)
#include <cerrno>
#include <cstdio>

#include "link.h"

namespace vb::sserial {

namespace {

constexpr int kOuts = 6;
constexpr unsigned kWidth = 15;
constexpr double kFullV = 10.0;
constexpr double kFullCounts = 16383.0;

class R7i77Analog final : public Personality {
  public:
    explicit R7i77Analog(uint32_t unit) : unit_(unit) {}
    std::string type() const override { return "7i77"; }
    std::array<uint8_t, 4> name() const override { return {'7', 'I', '7', '7'}; }
    uint32_t unit() const override { return unit_; }

    bool start(uint8_t mode, uint8_t &in_bits, uint8_t &out_bits) override
    {
        if (mode != 0)
            return false;
        in_bits = 0;
        out_bits = kOuts * kWidth + 1;
        return true;
    }

    void process(const std::vector<uint8_t> &out, std::vector<uint8_t> &in,
                 uint8_t &status) override
    {
        (void)in;
        for (int k = 0; k < kOuts; k++) {
            uint32_t raw = get_bits(out, kWidth * static_cast<unsigned>(k), kWidth);
            raw_[k] = (raw & (1u << (kWidth - 1))) ? static_cast<int>(raw) - (1 << kWidth)
                                                   : static_cast<int>(raw);
        }
        enable_ = get_bits(out, kOuts * kWidth, 1) != 0;
        status = 0;
    }

    int set(const std::vector<std::string> &args, std::string &err) override
    {
        (void)args;
        err = "7i77 analog channel: nothing to set (its outputs come from the host)";
        return -EINVAL;
    }

    std::string json() const override
    {
        char b[512];
        int n = std::snprintf(b, sizeof b,
                              "\"type\": \"7i77\", \"part\": \"analog\", \"unit\": %u, "
                              "\"analogena\": %s, \"analogout_raw\": [",
                              unit_, enable_ ? "true" : "false");
        for (int k = 0; k < kOuts; k++)
            n += std::snprintf(b + n, sizeof b - static_cast<size_t>(n), "%s%d", k ? ", " : "",
                               raw_[k]);
        n += std::snprintf(b + n, sizeof b - static_cast<size_t>(n), "], \"analogout_v\": [");
        for (int k = 0; k < kOuts; k++)
            n += std::snprintf(b + n, sizeof b - static_cast<size_t>(n), "%s%.6f",
                               k ? ", " : "", raw_[k] * kFullV / kFullCounts);
        std::snprintf(b + n, sizeof b - static_cast<size_t>(n), "]");
        return b;
    }

  private:
    uint32_t unit_;
    int raw_[kOuts] = {0, 0, 0, 0, 0, 0};
    bool enable_ = false;
};

} // namespace

std::unique_ptr<Personality> make_7i77_analog(uint32_t unit)
{
    return std::make_unique<R7i77Analog>(unit);
}

} // namespace vb::sserial
