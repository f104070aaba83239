// SPDX-License-Identifier: GPL-2.0-or-later
//
// Unit tests of the pin layer (src/pins.h) and the firmware image parser
// (src/fwimage.h), without any Verilated firmware: levels and precedence,
// probe statistics against hand-computed pulse trains, quadrature edge
// times against t0 + round(k * 1e9 / rate), image checks against a
// reference CRC-32 (the zlib check value of "123456789").
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "fwimage.h"
#include "pins.h"

namespace {

int failures = 0;

#define CHECK(cond)                                                                                \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            std::fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);          \
            failures++;                                                                            \
        }                                                                                          \
    } while (0)

vb_pin probe1(const vb::PinBank &b, uint32_t pin, uint64_t now)
{
    std::vector<vb_pin> v;
    std::string err;
    CHECK(b.probe(pin, 1, now, v, err) == 0);
    return v.empty() ? vb_pin{} : v[0];
}

void set_out(vb::PinBank &b, uint32_t pin, bool oe, bool out, uint64_t now, uint32_t *o,
             uint32_t *e)
{
    o[pin / 32] = (o[pin / 32] & ~(1u << (pin % 32))) | (uint32_t(out) << (pin % 32));
    e[pin / 32] = (e[pin / 32] & ~(1u << (pin % 32))) | (uint32_t(oe) << (pin % 32));
    b.set_fpga(o, e, now);
}

void test_levels_and_precedence()
{
    vb::PinBank b(40);
    uint32_t o[2] = {0, 0}, e[2] = {0, 0};
    std::string err;
    CHECK(b.level(0) && b.level(39)); // pull-ups
    CHECK(b.drive(3, VB_DRIVE_LOW, 10, err) == 0 && !b.level(3));
    set_out(b, 3, true, true, 20, o, e); // FPGA beats the external drive
    CHECK(b.level(3));
    set_out(b, 3, false, true, 30, o, e);
    CHECK(!b.level(3));
    CHECK(b.drive(3, VB_DRIVE_RELEASE, 40, err) == 0 && b.level(3));
    // loops: 5 -> 6 inverted -> 7
    CHECK(b.loop(5, 6, true, 50, err) == 0 && b.loop(6, 7, false, 50, err) == 0);
    set_out(b, 5, true, false, 60, o, e);
    CHECK(!b.level(5) && b.level(6) && b.level(7));
    set_out(b, 5, true, true, 70, o, e);
    CHECK(b.level(5) && !b.level(6) && !b.level(7));
    CHECK(b.loop(5, UINT32_MAX, false, 80, err) == 0 && b.level(6) && b.level(7));
    // a loop cycle does not recurse forever
    CHECK(b.loop(8, 9, true, 90, err) == 0 && b.loop(9, 8, false, 90, err) == 0);
    // errors leave the state alone
    CHECK(b.drive(40, VB_DRIVE_LOW, 100, err) == -EINVAL && err.find("pin 40") != std::string::npos);
    CHECK(b.drive(1, 7, 100, err) == -EINVAL);
    CHECK(b.loop(1, 1, false, 100, err) == -EINVAL);
    CHECK(b.loop(1, 45, false, 100, err) == -EINVAL);
    std::vector<vb_pin> v;
    CHECK(b.probe(39, 2, 100, v, err) == -EINVAL && v.empty());
    CHECK(b.probe(0, UINT32_MAX, 100, v, err) == -EINVAL);
}

void test_pulse_statistics()
{
    vb::PinBank b(1);
    uint32_t o[1] = {0}, e[1] = {1};
    std::string err;
    CHECK(b.probe_reset(0, 1, 0, err) == 0);
    // Output 0 from t=0 (a fall at 0), then pulses: high 30 ns every 100 ns,
    // one short 10 ns pulse at the end.
    b.set_fpga(o, e, 0);
    uint64_t t = 0;
    for (int k = 0; k < 5; k++) {
        t = 100 + uint64_t(k) * 100;
        o[0] = 1;
        b.set_fpga(o, e, t);
        o[0] = 0;
        b.set_fpga(o, e, t + 30);
    }
    o[0] = 1;
    b.set_fpga(o, e, 600);
    o[0] = 0;
    b.set_fpga(o, e, 610);
    vb_pin p = probe1(b, 0, 650);
    CHECK(p.rising == 6 && p.falling == 7);
    CHECK(p.last_high_ns == 10 && p.min_high_ns == 10);
    CHECK(p.last_low_ns == 70 && p.min_low_ns == 70);
    CHECK(p.period_ns == 100);
    CHECK(p.high_total_ns == 5 * 30 + 10);
    CHECK(p.total_ns == 650);
    // while high, the running interval counts toward the duty
    o[0] = 1;
    b.set_fpga(o, e, 700);
    p = probe1(b, 0, 725);
    CHECK(p.high_total_ns == 5 * 30 + 10 + 25 && p.level == 1 && p.oe == 1);
    CHECK(b.probe_reset(0, 1, 800, err) == 0);
    p = probe1(b, 0, 900);
    CHECK(p.rising == 0 && p.high_total_ns == 100 && p.total_ns == 100);
    CHECK(p.min_high_ns == UINT64_MAX && p.period_ns == 0);
}

void test_quadrature_times()
{
    vb::PinBank b(4);
    std::string err;
    vb_quad q{0, 1, 2, 8, 300000.0}; // A=0 B=1 I=2, 1/3 us per count
    CHECK(b.quad(q, 1000, err) == 0);
    CHECK(b.next_event_ns() == 1000 + 3333); // round(1e9/3e5)
    uint64_t last = 0;
    for (int k = 1; k <= 40; k++) {
        uint64_t want = 1000 + uint64_t(std::llround(k * 1e9 / 300000.0));
        CHECK(b.next_event_ns() == want);
        last = b.next_event_ns();
        b.run_events(last);
    }
    // 40 counts: A had 10 rising edges, index high at multiples of 8
    vb_pin a = probe1(b, 0, last);
    CHECK(a.rising == 10);
    vb_pin i = probe1(b, 2, last);
    CHECK(i.level == 1 && i.rising == 5); // position 40 = 5 * 8
    // reverse and stop
    q.counts_per_s = -1e6;
    CHECK(b.quad(q, last, err) == 0 && b.next_event_ns() == last + 1000);
    q.counts_per_s = 0;
    CHECK(b.quad(q, last, err) == 0 && b.next_event_ns() == vb::PinBank::kNever);
    q.pin_b = 0;
    CHECK(b.quad(q, last, err) == -EINVAL);
    q = vb_quad{0, 1, UINT32_MAX, 0, 1e12};
    CHECK(b.quad(q, last, err) == -EINVAL);
}

void put32(uint8_t *p, uint32_t v) { std::memcpy(p, &v, 4); }

void test_fw_image()
{
    const uint8_t check[] = "123456789";
    CHECK(vb::crc32(check, 9) == 0xCBF43926u); // the standard CRC-32 check value
    uint8_t img[68] = {};
    put32(img, vb::kFwMagic);
    put32(img + 4, 1);
    put32(img + 8, 68);
    put32(img + 12, 0x11223344u);
    std::memcpy(img + 16, "5i20", 4);
    std::memcpy(img + 32, "SVST8_4", 7);
    put32(img + 64, vb::crc32(img, 64));
    vb::FwImage fw;
    std::string err;
    CHECK(vb::parse_fw_image(img, 68, fw, err) == 0);
    CHECK(fw.board == "5i20" && fw.firmware == "SVST8_4" && fw.idrom_crc == 0x11223344u);
    CHECK(vb::parse_fw_image(img, 67, fw, err) == -EINVAL && err.find("truncated") != std::string::npos);
    CHECK(vb::parse_fw_image(img, 0, fw, err) == -EINVAL);
    img[40] ^= 1;
    CHECK(vb::parse_fw_image(img, 68, fw, err) == -EINVAL && err.find("corrupt") != std::string::npos);
    img[40] ^= 1;
    std::memset(img + 16, 'x', 16); // name without NUL
    put32(img + 64, vb::crc32(img, 64));
    CHECK(vb::parse_fw_image(img, 68, fw, err) == -EINVAL && err.find("malformed") != std::string::npos);
    img[0] = 0;
    CHECK(vb::parse_fw_image(img, 68, fw, err) == -EINVAL && err.find("bad magic") != std::string::npos);
}

} // namespace

int main()
{
    test_levels_and_precedence();
    test_pulse_statistics();
    test_quadrature_times();
    test_fw_image();
    if (failures)
        std::fprintf(stderr, "vboard unit tests: %d failure(s)\n", failures);
    else
        std::printf("vboard unit tests: ok\n");
    return failures ? 1 : 0;
}
