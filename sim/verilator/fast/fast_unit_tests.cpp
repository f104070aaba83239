// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_unit_tests.cpp - ctest vboard_fast_unit_tests: the fast model's IDROM
// reader (coverage refusals name the module) and its DDS closed forms
// against a clock-by-clock accumulator.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "fast_config.h"
#include "fast_idroms.h"
#include "fast_model.h"
#include "fast_modules.h"

namespace {

int failures = 0;

void check(bool ok, const std::string &what)
{
    if (!ok) {
        std::fprintf(stderr, "FAIL: %s\n", what.c_str());
        failures++;
    }
}

void test_config()
{
    using namespace vb::fast;
    const uint32_t *w = find_idrom("5i20", "SVST8_4");
    check(w != nullptr, "the 5i20 SVST8_4 IDROM is in the table");
    if (!w)
        return;
    Config cfg;
    std::string err;
    check(parse_config(w, cfg, err) == 0, "SVST8_4 parses: " + err);
    check(cfg.io_width == 72 && cfg.io_ports == 3 && cfg.port_width == 24, "SVST8_4 I/O");
    check(cfg.clock_low_hz == 33333333 && cfg.clock_high_hz == 100000000, "SVST8_4 clocks");
    check(cfg.modules.size() == 6, "SVST8_4 has 6 module descriptors");
    const ModuleDesc *enc = cfg.find(kTagEncoder);
    check(enc && enc->instances == 8 && enc->base == 0x3000, "SVST8_4 encoders");
    check(fast_coverage(w).empty(), "SVST8_4 is covered");

    // An SSerial module descriptor after the last one: refused, by name.
    uint32_t img[256];
    std::memcpy(img, w, sizeof img);
    uint32_t md = img[1] / 4 + 3 * static_cast<uint32_t>(cfg.modules.size());
    img[md] = 0x010100C1u;
    img[md + 1] = 0x00055A00u;
    std::string why = fast_coverage(img);
    check(why.find("does not cover module SSerial") != std::string::npos,
          "an SSerial module is refused by name: '" + why + "'");
    check(parse_config(img, cfg, err) == -ENOTSUP, "refusal is -ENOTSUP");

    // A module version the models do not transcribe: refused with it.
    std::memcpy(img, w, sizeof img);
    uint32_t enc_md = img[1] / 4 + 3 * 2; // SVST8_4: Watchdog, IOPort, Encoder
    img[enc_md] = (img[enc_md] & ~0xff00u) | 0x0700u;
    why = fast_coverage(img);
    check(why.find("does not cover module Encoder version 0x07") != std::string::npos,
          "an unknown Encoder version is refused: '" + why + "'");

    std::memcpy(img, w, sizeof img);
    img[2] = 4000; // pin descriptors outside the IDROM
    check(parse_config(img, cfg, err) == -EINVAL && err.find("outside") != std::string::npos,
          "a bad pin-descriptor offset is refused: " + err);
}

// The DDS closed forms against the accumulator run clock by clock.
void test_dds()
{
    using vb::fast::Dds;
    std::mt19937_64 rng(7);
    for (int trial = 0; trial < 2000; trial++) {
        unsigned bits = trial % 2 ? 16 : 32;
        uint64_t mod = 1ull << bits;
        uint64_t rate = rng() % mod;
        if (trial % 7 == 0)
            rate = rng() % 64;
        uint64_t phase = rng() % mod;
        bool tick = rng() % 2;
        uint64_t n = 1 + rng() % 3000;
        // brute force: ticks seen by a consumer over n edges
        uint64_t p = phase, seen = 0;
        bool t = tick;
        for (uint64_t e = 0; e < n; e++) {
            seen += t;
            uint64_t s = p + rate;
            t = s >= mod;
            p = s % mod;
        }
        check(Dds::ticks(tick, phase, rate, bits, n) == seen, "Dds::ticks");
        bool t2 = tick;
        uint64_t p2 = phase;
        Dds::advance(t2, p2, rate, bits, n);
        check(t2 == t && p2 == p, "Dds::advance");
        // edges_for(k): the largest n with ticks(n) <= k
        uint64_t k = seen;
        uint64_t m = Dds::edges_for(tick, phase, rate, bits, k);
        if (m != vb::fast::kForever) {
            check(Dds::ticks(tick, phase, rate, bits, m) <= k, "edges_for: within k");
            check(Dds::ticks(tick, phase, rate, bits, m + 1) > k, "edges_for: the largest");
        } else {
            check(rate == 0, "edges_for: forever only at rate 0");
        }
    }
}

} // namespace

int main()
{
    test_config();
    test_dds();
    if (failures) {
        std::fprintf(stderr, "vboard_fast_unit_tests: %d failures\n", failures);
        return 1;
    }
    std::printf("vboard_fast_unit_tests: all passed\n");
    return 0;
}
