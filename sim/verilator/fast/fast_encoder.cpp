// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_encoder.cpp - the Encoder bank model (see fast_encoder.h).
#include "fast_encoder.h"

namespace vb::fast {

namespace {
constexpr int kAbMaskPol = 14, kLatchPrb = 13, kProbePol = 12, kQfilter = 11, kUpDown = 10, kUseMask = 9, kMaskPol = 8,
              kAbGate = 7, kJustOnce = 6, kClrIdx = 5, kLatchIdx = 4, kIdxPol = 3;
inline bool bit(uint32_t v, int n) { return (v >> n) & 1u; }
// the filter's inputs from the synchronized pins: A, B, Index, Probe
inline uint8_t fin(uint8_t s) { return static_cast<uint8_t>((s & 7) | ((s >> 1) & 8)); }

// A prescaler that ticks when pre >= div + 1 or div's top bit is set, then
// restarts at 0: ticks over n edges and the prescaler after them.
uint64_t prescale(uint32_t &pre, uint32_t div, bool top, uint32_t mask, uint64_t n,
                  bool &last_tick)
{
    if (n == 0)
        return 0;
    if (top) {
        pre = 0;
        last_tick = true;
        return n;
    }
    uint64_t period = static_cast<uint64_t>(div) + 2;
    uint64_t first = pre >= div + 1 ? 1 : static_cast<uint64_t>(div) + 1 - pre + 1;
    if (n < first) {
        pre = static_cast<uint32_t>((pre + n) & mask);
        last_tick = false;
        return 0;
    }
    uint64_t after = n - first; // edges after the first tick
    pre = static_cast<uint32_t>(after % period);
    last_tick = pre == 0;
    return 1 + after / period;
}
} // namespace

EncoderBank::EncoderBank(uint16_t base, uint32_t clock_low_hz,
                         std::vector<std::array<int, 5>> pins)
    : page_(static_cast<uint8_t>(base >> 8)), pins_(std::move(pins)), enc_(pins_.size())
{
    uint32_t div = (clock_low_hz + 8000000u) / 16000000u;
    qfilter_reset_ = div >= 2 ? static_cast<uint16_t>((div - 2) & 0xfff) : 0xfff;
    qfilter_ = qfilter_reset_;
}

uint8_t EncoderBank::pins_of(size_t i, const uint32_t *in) const
{
    uint8_t d = 0;
    for (int k = 0; k < 5; k++) {
        int p = pins_[i][k];
        if (p >= 0 && ((in[p >> 5] >> (p & 31)) & 1u))
            d |= static_cast<uint8_t>(1u << k);
    }
    return d;
}

uint32_t EncoderBank::read(uint16_t addr) const
{
    uint8_t page = static_cast<uint8_t>(addr >> 8);
    uint8_t off = static_cast<uint8_t>(page - page_);
    uint32_t inst = (addr >> 2) & 63;
    if (inst >= enc_.size() || page < page_ || off >= 5)
        return 0;
    const Enc &e = enc_[inst];
    switch (off) {
    case 0: return static_cast<uint32_t>(e.stamp) << 16 | e.count;
    case 1:
        return static_cast<uint32_t>(e.latch) << 16 | (e.qerr ? 1u << 15 : 0u) |
               (e.ctrl & 0x7ff8u) | (e.filt & 7);
    case 2: return inst == 0 ? tsdiv_ : 0;
    case 3: return inst == 0 ? tscount_ : 0;
    default: return inst == 0 ? qfilter_ : 0;
    }
}

bool EncoderBank::cond(const Enc &e) const
{
    bool a = e.filt & 1, b = e.filt & 2, idx = e.filt & 4;
    bool mask_ok = !bit(e.ctrl, kUseMask) || (bit(e.s2, 3) == bit(e.ctrl, kMaskPol));
    bool ab_ok = !bit(e.ctrl, kAbGate) ||
                 (a == bit(e.ctrl, kAbMaskPol) && b == bit(e.ctrl, kAbMaskPol));
    return idx == bit(e.ctrl, kIdxPol) && mask_ok && ab_ok;
}

void EncoderBank::enc_edge(Enc &e, uint8_t d, bool we_count, bool we_ccr, uint32_t wdata)
{
    uint8_t ps = fin(e.s2);
    uint8_t fmax = bit(e.ctrl, kQfilter) ? 15 : 3;
    // decoder, from the state before the edge
    bool a = e.filt & 1, b = (e.filt >> 1) & 1;
    bool pa = e.prev & 1, pb = (e.prev >> 1) & 1;
    bool up = false, down = false, qerr_set = false;
    if (!e.live) {
    } else if (bit(e.ctrl, kUpDown)) {
        if (a && !pa) { // B as it was before the A edge
            up = pb;
            down = !pb;
        }
    } else if ((a != pa) && (b != pb)) {
        qerr_set = true;
    } else if (a != pa) {
        up = a != b;
        down = a == b;
    } else if (b != pb) {
        up = a == b;
        down = a != b;
    }
    bool c = cond(e);
    bool index_event = e.live && c && !e.cond_prev;
    bool do_clear = index_event && bit(e.ctrl, kClrIdx);
    bool do_latch = index_event && bit(e.ctrl, kLatchIdx);
    bool prb = bit(e.filt, 3);
    bool probe_edge = e.live && prb != e.probe_prev && prb == bit(e.ctrl, kProbePol);
    bool do_probe = probe_edge && bit(e.ctrl, kLatchPrb);

    // filter
    Enc n = e;
    if (!e.primed) {
        if (e.warm != 3) {
            n.warm = static_cast<uint8_t>(e.warm + 1);
        } else {
            n.filt = ps & 15;
            for (int j = 0; j < 4; j++)
                n.fcnt[j] = bit(ps, j) ? fmax : 0;
            n.primed = true;
        }
    } else {
        n.live = true;
        if (sample_) {
            for (int j = 0; j < 4; j++) {
                uint8_t f = e.fcnt[j];
                if (bit(ps, j)) {
                    if (f + 1 >= fmax) {
                        n.fcnt[j] = fmax;
                        n.filt = static_cast<uint8_t>(n.filt | (1u << j));
                    } else {
                        n.fcnt[j] = static_cast<uint8_t>(f + 1);
                    }
                } else {
                    if (f <= 1) {
                        n.fcnt[j] = 0;
                        n.filt = static_cast<uint8_t>(n.filt & ~(1u << j));
                    } else if (f > fmax) {
                        n.fcnt[j] = static_cast<uint8_t>(fmax - 1);
                    } else {
                        n.fcnt[j] = static_cast<uint8_t>(f - 1);
                    }
                }
            }
        }
    }
    // decoder registers
    n.prev = e.filt & 3;
    n.cond_prev = c;
    n.probe_prev = prb;
    if (we_count || do_clear)
        n.count = 0;
    else if (up)
        n.count = static_cast<uint16_t>(e.count + 1);
    else if (down)
        n.count = static_cast<uint16_t>(e.count - 1);
    if (up || down)
        n.stamp = tscount_;
    if (do_probe || do_latch)
        n.latch = e.count;
    if (we_ccr) {
        n.ctrl = static_cast<uint16_t>(wdata & 0x7ff8u);
    } else if (bit(e.ctrl, kJustOnce)) {
        uint32_t clr = (index_event ? (1u << kClrIdx) | (1u << kLatchIdx) : 0u) |
                       (do_probe ? 1u << kLatchPrb : 0u);
        n.ctrl = static_cast<uint16_t>(e.ctrl & ~clr);
    }
    if (qerr_set)
        n.qerr = true;
    else if (we_ccr && bit(wdata, 15))
        n.qerr = false;
    n.s2 = e.s1;
    n.s1 = d;
    e = n;
}

void EncoderBank::edge(const Bus &b, bool rst, const uint32_t *in)
{
    if (rst) {
        for (Enc &e : enc_)
            e = Enc{};
        tsdiv_ = tspre_ = tscount_ = fpre_ = 0;
        qfilter_ = qfilter_reset_;
        sample_ = false;
        return;
    }
    uint8_t page = b.page();
    uint8_t off = static_cast<uint8_t>(page - page_);
    uint32_t inst = b.inst();
    bool in_range = page >= page_ && off < 5;
    bool ts_tick = (tsdiv_ >> 15) || tspre_ >= static_cast<uint32_t>(tsdiv_) + 1;
    bool f_tick = (qfilter_ >> 11) || fpre_ >= static_cast<uint32_t>(qfilter_) + 1;
    for (size_t i = 0; i < enc_.size(); i++) {
        Enc &e = enc_[i];
        bool sel = b.we && in_range && inst == i;
        uint8_t d = pins_of(i, in);
        if (e.quiet && !sel && d == e.s1)
            continue; // steady, same inputs, not written: nothing changes
        enc_edge(e, d, sel && off == 0, sel && off == 1, b.wdata);
        e.quiet = steady(e, d);
    }
    if (b.we && in_range && inst == 0 && off == 2)
        tsdiv_ = static_cast<uint16_t>(b.wdata);
    if (b.we && in_range && inst == 0 && off == 4)
        qfilter_ = static_cast<uint16_t>(b.wdata & 0xfff);
    if (ts_tick) {
        tspre_ = 0;
        tscount_++;
    } else {
        tspre_++;
    }
    sample_ = f_tick;
    fpre_ = f_tick ? 0 : static_cast<uint16_t>((fpre_ + 1) & 0xfff);
}

bool EncoderBank::steady(const Enc &e, uint8_t d) const
{
    if (!e.primed || !e.live || e.s1 != d || e.s2 != d)
        return false;
    uint8_t fmax = bit(e.ctrl, kQfilter) ? 15 : 3;
    uint8_t f = fin(d);
    for (int j = 0; j < 4; j++) {
        bool p = bit(f, j);
        if (p ? (e.fcnt[j] != fmax || !bit(e.filt, j)) : (e.fcnt[j] != 0 || bit(e.filt, j)))
            return false;
    }
    return e.prev == (e.filt & 3) && e.cond_prev == cond(e) && e.probe_prev == bit(e.filt, 3);
}

uint64_t EncoderBank::horizon(const uint32_t *in) const
{
    for (size_t i = 0; i < enc_.size(); i++)
        if (!steady(enc_[i], pins_of(i, in)))
            return 0;
    return kForever;
}

void EncoderBank::skip(uint64_t n)
{
    if (n == 0)
        return;
    uint32_t pre = tspre_;
    bool last = false;
    uint64_t t = prescale(pre, tsdiv_, tsdiv_ >> 15, 0xffff, n, last);
    tspre_ = static_cast<uint16_t>(pre);
    tscount_ = static_cast<uint16_t>(tscount_ + t);
    pre = fpre_;
    prescale(pre, qfilter_, qfilter_ >> 11, 0xfff, n, last);
    fpre_ = static_cast<uint16_t>(pre);
    sample_ = last;
}

} // namespace vb::fast
