// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_encoder.h - the Encoder bank (hm2_encoder_bank.v, hm2_encoder.v):
// timestamp and filter prescalers shared by the bank, per instance a 2-flop
// synchronizer, the A/B/Index/Probe digital filter, the quadrature decoder,
// the index and probe latches and the CCR.  Steady state: every instance's synchronizer and
// filter agree with constant pins and the decoder has seen the last change;
// then only the prescalers move, in closed form.
#ifndef VBOARD_FAST_ENCODER_H
#define VBOARD_FAST_ENCODER_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fast_modules.h"

namespace vb::fast {

class EncoderBank {
  public:
    // pins[i] = I/O pin of instance i's A, B, Index, IndexMask, Probe (-1: tied low)
    EncoderBank(uint16_t base, uint32_t clock_low_hz, std::vector<std::array<int, 5>> pins);
    uint32_t read(uint16_t addr) const;
    void edge(const Bus &b, bool rst, const uint32_t *in);
    uint64_t horizon(const uint32_t *in) const;
    void skip(uint64_t n);

  private:
    struct Enc {
        uint8_t s1 = 0, s2 = 0;  // synchronizer stages {probe, mask, idx, b, a}
        uint16_t ctrl = 0;       // CCR bits 14..3 at their positions
        bool qerr = false;
        uint8_t fcnt[4] = {0, 0, 0, 0}; // A, B, Index, Probe
        uint8_t filt = 0, prev = 0;     // filt: {Probe, Index, B, A}
        bool cond_prev = false, probe_prev = false;
        uint16_t count = 0, stamp = 0, latch = 0;
        uint8_t warm = 0;
        bool primed = false, live = false;
        bool quiet = false; // steady for the inputs s1 holds: an idle edge is the identity
    };
    uint8_t pins_of(size_t i, const uint32_t *in) const;
    bool cond(const Enc &e) const;
    bool steady(const Enc &e, uint8_t d) const;
    void enc_edge(Enc &e, uint8_t d, bool we_count, bool we_ccr, uint32_t wdata);

    uint8_t page_;
    uint16_t qfilter_reset_;
    std::vector<std::array<int, 5>> pins_;
    std::vector<Enc> enc_;
    uint16_t tsdiv_ = 0, tspre_ = 0, tscount_ = 0, qfilter_ = 0, fpre_ = 0;
    bool sample_ = false;
};

} // namespace vb::fast

#endif // VBOARD_FAST_ENCODER_H
