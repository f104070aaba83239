// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_pwm.h - the PWMGen bank (hm2_pwmgen_bank.v, hm2_pwmgen.v): bus
// registers and the request/acknowledge handshake on ClockLow, the shared
// PWM/PDM rate DDSs, the reference counter and per instance the comparator,
// PDM accumulator and output mode on ClockHigh.  Once a configuration has
// crossed over and every output agrees with its comparator, the next output
// edge is where the reference counter next reaches a compare point (or a
// double-buffered value loads at a cycle start, or a PDM output could
// change): horizon_high() counts the ClockHigh edges to it through the
// DDS, skip_high() jumps there.
#ifndef VBOARD_FAST_PWM_H
#define VBOARD_FAST_PWM_H

#include <cstdint>
#include <vector>

#include "fast_modules.h"

namespace vb::fast {

class PwmBank {
  public:
    PwmBank(uint16_t base, uint32_t instances);
    uint32_t read(uint16_t addr) const;
    bool ack_h() const { return ack_h_; }
    // ClockHigh edge; rst is the (ClockLow) reset input.  True when an
    // output (out0, out1) changed.
    bool high_edge(bool rst);
    // ClockLow edge; ack_h_pre: the ClockHigh acknowledge before this edge
    void low_edge(const Bus &b, bool rst, bool ack_h_pre);
    // ClockHigh edges that may pass in closed form (0 while a transfer or a
    // reset is on its way, or an output is about to change)
    uint64_t horizon_high() const;
    void skip_high(uint64_t n);
    // A ClockLow edge with the bus not writing while horizon_high() >= 1:
    // the ClockLow side is settled, so its edge is the identity; the
    // ClockHigh edge at the same time passes in closed form.
    bool idle_low_edge_ok(const Bus &b) const { return !b.we && horizon_high() >= 1; }
    bool out0(uint32_t i) const { return inst_[i].out0; }
    bool out1(uint32_t i) const { return inst_[i].out1; }
    bool nenable(uint32_t i) const { return (nenable_ >> i) & 1u; }

  private:
    struct Cfg {
        std::vector<uint16_t> val; // {DIR, value[11:0]}
        std::vector<uint8_t> mode;
        uint16_t pwmrate = 0, pdmrate = 0;
    };
    struct Inst {
        uint16_t act = 0, pdm_acc = 0;
        bool pdm = false, pwm = false, dir = false, out0 = false, out1 = false;
    };
    static uint16_t span(uint8_t mode);
    static bool cmp_lt(uint16_t ref, uint8_t mode, uint16_t act);
    static void out_map(uint8_t mode, bool pwm, bool dir, bool pdm, bool &o0, bool &o1);
    uint64_t ticks_to_change(uint32_t i) const;
    uint64_t compute_horizon() const;
    // horizon_high() cache: valid until a stepped edge changes the state
    mutable bool h_valid_ = false;
    mutable uint64_t h_ = 0;

    uint8_t page_;
    uint32_t num_;
    // ClockLow side
    Cfg reg_, xfer_;
    uint32_t enable_ = 0, nenable_;
    bool dirty_ = false, busy_ = false, req_ = false;
    bool ack1_ = false, ack2_ = false; // ack synchronizer (no reset)
    // ClockHigh side
    bool r1_ = false, r2_ = false;     // reset synchronizer (no reset)
    bool q1_ = false, q2_ = false;     // req synchronizer (reset by rst_h)
    bool ack_h_ = false;
    Cfg cfg_;
    uint64_t pwm_phase_ = 0, pdm_phase_ = 0;
    bool pwm_tick_ = false, pdm_tick_ = false;
    uint16_t ref_ = 0;
    std::vector<Inst> inst_;
};

} // namespace vb::fast

#endif // VBOARD_FAST_PWM_H
