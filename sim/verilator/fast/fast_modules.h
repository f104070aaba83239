// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_modules.h - C++ models of the hm2 modules, each a cycle-exact
// transcription of its Verilog (hdl/hostmot2/hm2_*.v) plus a closed form for
// its steady state.
//
// Every ClockLow-domain module has
//   read(addr)         the word its bus_rdata register takes on a read of
//                      addr (from the state before the clock edge);
//   edge(bus, rst,...) one ClockLow rising edge: the next state from the
//                      state before the edge (nonblocking semantics);
//   horizon(...)       how many of the next ClockLow edges it can let pass in
//                      closed form while the bus is idle and its inputs keep
//                      their present levels: edges that change no output, no
//                      read-back value other than free-running counters, and
//                      no state except in the way skip() reproduces;
//   skip(n)            those n edges at once (n <= horizon).
// The PWMGen bank also runs on ClockHigh (fast_pwm.h).
#ifndef VBOARD_FAST_MODULES_H
#define VBOARD_FAST_MODULES_H

#include <cstdint>
#include <limits>
#include <vector>

namespace vb::fast {

constexpr uint64_t kForever = std::numeric_limits<uint64_t>::max();

// The registered internal bus (hm2_localbus outputs) before an edge.
struct Bus {
    uint16_t addr = 0;
    uint32_t wdata = 0;
    bool we = false, re = false;
    uint8_t page() const { return static_cast<uint8_t>(addr >> 8); }
    uint8_t inst() const { return static_cast<uint8_t>((addr >> 2) & 63); }
};

// A DDS accumulator of `bits` bits whose registered carry is a tick: the
// number of ticks seen over the next n edges and its inverse.
struct Dds {
    // ticks the consumer sees over the next n edges (tick register first)
    static uint64_t ticks(bool tick, uint64_t phase, uint64_t rate, unsigned bits, uint64_t n);
    // the largest n whose ticks(n) <= k (kForever when no limit)
    static uint64_t edges_for(bool tick, uint64_t phase, uint64_t rate, unsigned bits, uint64_t k);
    // advance by n edges: new phase and tick register
    static void advance(bool &tick, uint64_t &phase, uint64_t rate, unsigned bits, uint64_t n);
};

class Idrom {
  public:
    explicit Idrom(const uint32_t *words);
    uint32_t read(uint16_t addr) const;
    void edge(const Bus &b, bool rst);

  private:
    uint32_t mem_[256];
    bool wen_ = false;
};

class Watchdog {
  public:
    explicit Watchdog(uint16_t base) : page_(static_cast<uint8_t>(base >> 8)) {}
    uint32_t read(uint16_t addr) const;
    void edge(const Bus &b, bool rst);
    bool bite() const { return bite_; }
    uint64_t horizon() const;
    void skip(uint64_t n) { if (!(timer_ >> 31)) timer_ -= static_cast<uint32_t>(n); }

  private:
    uint8_t page_;
    uint32_t timer_ = 0, reload_ = 0;
    bool status_ = false, under_ = false, bite_ = false;
};

class Led {
  public:
    explicit Led(uint16_t base) : page_(static_cast<uint8_t>(base >> 8)) {}
    void edge(const Bus &b, bool rst);
    uint32_t leds() const { return led_; }

  private:
    uint8_t page_;
    uint32_t led_ = 0; // bus_wdata bits 31..(32-N): the LED register as written
};

// IOPort bank: ports of `width` pins, pin p of port k is I/O pin k*width+p.
class IoPort {
  public:
    IoPort(uint16_t base, uint32_t ports, uint32_t width);
    uint32_t read(uint16_t addr) const;
    // in: the pin levels (I/O pin vector, 32-bit words)
    void edge(const Bus &b, bool rst, bool bite, const uint32_t *in);
    // io_out, io_oe from the registers and the modules' outputs alt (pin vectors)
    void outputs(const uint32_t *alt, uint32_t *out, uint32_t *oe) const;
    uint64_t horizon(const uint32_t *in) const;

  private:
    uint32_t port_bits(const uint32_t *v, uint32_t port) const;
    uint8_t page_;
    uint32_t ports_, width_, mask_;
    std::vector<uint32_t> data_, ddr_, alt_, od_, inv_, s1_, s2_;
};

} // namespace vb::fast

#endif // VBOARD_FAST_MODULES_H
