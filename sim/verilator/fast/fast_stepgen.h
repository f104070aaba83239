// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_stepgen.h - the StepGen bank (hm2_stepgen_bank.v, hm2_stepgen.v): the
// master DDS whose carry is the basic-rate tick, and per instance the 48-bit
// accumulator, the step/dir, up/down, quadrature and table sequencers with
// their timing counters.  Between events the accumulators and counters are
// linear in the number of ticks and edges: horizon() finds the next edge at
// which an instance could cross a step boundary, end a pulse, change its
// direction or its output, and skip() jumps there in closed form.
#ifndef VBOARD_FAST_STEPGEN_H
#define VBOARD_FAST_STEPGEN_H

#include <cstdint>
#include <vector>

#include "fast_modules.h"

namespace vb::fast {

class StepgenBank {
  public:
    static constexpr unsigned kTableWidth = 8; // outputs modelled per instance
    StepgenBank(uint16_t base, uint32_t instances);
    uint32_t read(uint16_t addr) const;
    void edge(const Bus &b, bool rst);
    uint64_t horizon() const;
    void skip(uint64_t n);
    // output k (0 = Step, 1 = Dir, 2.. = Table2..) of instance i
    bool out(uint32_t i, uint32_t k) const { return (sg_[i].out >> k) & 1u; }

  private:
    struct Sg {
        uint32_t rate = 0;
        uint64_t acc = 0; // 48 bits
        uint8_t mode = 0;
        bool swap = false; // Mode bit 2: Step and Dir pins exchanged
        uint16_t dirsetup = 0, dirhold = 0, pulsewidth = 0, pulseidle = 0;
        uint8_t table[16] = {};
        uint8_t tablelen = 0;
        bool pulse = false, dir = false;
        uint16_t width_cnt = 0, idle_cnt = 0, hold_cnt = 0, setup_cnt = 0;
        uint8_t ptr = 0;
        uint8_t out = 0;
    };
    static uint32_t rate_eff(const Sg &s);
    static uint8_t out_d(const Sg &s);
    static uint8_t out_mode(const Sg &s); // before the swap
    // ticks until the tick that makes the accumulator cross (kForever: never)
    static uint64_t ticks_to_cross(const Sg &s);
    uint64_t sg_horizon(const Sg &s) const;
    void sg_edge(Sg &s, const Bus &b, bool sel, uint8_t off);

    uint8_t page_;
    std::vector<Sg> sg_;
    uint32_t master_ = 0;
    uint64_t phase_ = 0;
    bool tick_ = false;
};

} // namespace vb::fast

#endif // VBOARD_FAST_STEPGEN_H
