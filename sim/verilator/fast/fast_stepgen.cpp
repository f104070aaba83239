// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_stepgen.cpp - the StepGen bank model (see fast_stepgen.h).
#include "fast_stepgen.h"

#include <algorithm>

namespace vb::fast {

namespace {
constexpr uint8_t kStepDir = 0, kUpDown = 1, kQuad = 2, kTable = 3;
constexpr uint64_t kMask48 = (1ull << 48) - 1;
inline uint64_t sext48(uint32_t r)
{
    return (r >> 31) ? (0xffff00000000ull | r) : r;
}
} // namespace

StepgenBank::StepgenBank(uint16_t base, uint32_t instances)
    : page_(static_cast<uint8_t>(base >> 8)), sg_(instances)
{
}

uint32_t StepgenBank::rate_eff(const Sg &s)
{
    bool neg = s.rate >> 31;
    if (s.mode == kQuad) {
        if (!neg && s.rate > 0x40000000u)
            return 0x40000000u;
        if (neg && s.rate < 0xC0000000u)
            return 0xC0000000u;
    }
    return s.rate;
}

uint8_t StepgenBank::out_d(const Sg &s)
{
    uint8_t o = out_mode(s);
    if (s.swap)
        o = static_cast<uint8_t>((o & ~3u) | ((o & 1) << 1) | ((o >> 1) & 1));
    return o;
}

uint8_t StepgenBank::out_mode(const Sg &s)
{
    switch (s.mode) {
    case kStepDir: return static_cast<uint8_t>((s.pulse ? 1 : 0) | (s.dir ? 2 : 0));
    case kUpDown: return static_cast<uint8_t>((s.pulse && !s.dir ? 1 : 0) | (s.pulse && s.dir ? 2 : 0));
    case kQuad: {
        bool b31 = (s.acc >> 31) & 1, b30 = (s.acc >> 30) & 1;
        return static_cast<uint8_t>((b31 ^ b30 ? 1 : 0) | (b31 ? 2 : 0));
    }
    default: return s.table[s.ptr];
    }
}

uint32_t StepgenBank::read(uint16_t addr) const
{
    uint8_t page = static_cast<uint8_t>(addr >> 8);
    uint8_t off = static_cast<uint8_t>(page - page_);
    uint32_t inst = (addr >> 2) & 63;
    if (inst >= sg_.size() || page < page_ || off >= 10)
        return 0;
    if (off == 1)
        return static_cast<uint32_t>(sg_[inst].acc >> 16);
    if (off == 9 && inst == 0)
        return master_;
    return 0;
}

void StepgenBank::sg_edge(Sg &s, const Bus &b, bool sel, uint8_t off)
{
    bool neg = s.rate >> 31;
    bool seq = s.mode & 2;
    uint64_t sum = (s.acc + sext48(rate_eff(s))) & kMask48;
    int cb = s.mode == kQuad ? 30 : 32;
    bool crosses = ((sum >> cb) ^ (s.acc >> cb)) & 1;
    bool event_ok = !s.pulse && s.idle_cnt == 0 && (seq || (s.dir == neg && s.setup_cnt == 0));
    bool do_event = tick_ && crosses && event_ok;
    bool do_add = tick_ && (!crosses || event_ok);
    bool dir_change = (neg != s.dir) && !s.pulse && s.hold_cnt == 0;
    uint8_t od = out_d(s);
    Sg n = s;
    uint32_t w = b.wdata;
    if (sel) {
        switch (off) {
        case 0: n.rate = w; break;
        case 2:
            n.mode = w & 3;
            n.swap = (w >> 2) & 1;
            break;
        case 3: n.dirsetup = w & 0x3fff; break;
        case 4: n.dirhold = w & 0x3fff; break;
        case 5: n.pulsewidth = w & 0x3fff; break;
        case 6: n.pulseidle = w & 0x3fff; break;
        case 7:
            for (int e = 15; e > 0; e--)
                n.table[e] = s.table[e - 1];
            n.table[0] = static_cast<uint8_t>(w);
            break;
        case 8: n.tablelen = w & 15; break;
        default: break;
        }
    }
    if (sel && off == 1)
        n.acc = static_cast<uint64_t>(w) << 16;
    else if (do_add)
        n.acc = sum;
    if (do_event) {
        n.pulse = true;
        n.width_cnt = s.pulsewidth;
    } else if (s.pulse) {
        if (s.width_cnt == 0) {
            n.pulse = false;
            n.idle_cnt = s.pulseidle;
            n.hold_cnt = s.dirhold;
        } else {
            n.width_cnt = static_cast<uint16_t>(s.width_cnt - 1);
        }
    } else {
        if (s.idle_cnt)
            n.idle_cnt = static_cast<uint16_t>(s.idle_cnt - 1);
        if (s.hold_cnt)
            n.hold_cnt = static_cast<uint16_t>(s.hold_cnt - 1);
    }
    if (dir_change) {
        n.dir = neg;
        n.setup_cnt = s.dirsetup;
    } else if (s.setup_cnt) {
        n.setup_cnt = static_cast<uint16_t>(s.setup_cnt - 1);
    }
    if (sel && off == 8)
        n.ptr = 0;
    else if (do_event && s.mode == kTable) {
        if (!neg)
            n.ptr = s.ptr == s.tablelen ? 0 : static_cast<uint8_t>((s.ptr + 1) & 15);
        else
            n.ptr = s.ptr == 0 ? s.tablelen : static_cast<uint8_t>(s.ptr - 1);
    }
    n.out = od;
    s = n;
}

void StepgenBank::edge(const Bus &b, bool rst)
{
    if (rst) {
        for (Sg &s : sg_)
            s = Sg{};
        master_ = 0;
        phase_ = 0;
        tick_ = false;
        return;
    }
    uint8_t page = b.page();
    uint8_t off = static_cast<uint8_t>(page - page_);
    uint32_t inst = b.inst();
    bool in_range = page >= page_ && off < 10;
    for (size_t i = 0; i < sg_.size(); i++)
        sg_edge(sg_[i], b, b.we && in_range && inst == i, off);
    uint64_t sum = phase_ + master_;
    if (b.we && in_range && off == 9 && inst == 0)
        master_ = b.wdata;
    phase_ = sum & 0xffffffffull;
    tick_ = sum >> 32;
}

uint64_t StepgenBank::ticks_to_cross(const Sg &s)
{
    uint64_t r = sext48(rate_eff(s));
    if (r == 0)
        return kForever;
    uint64_t g = s.mode == kQuad ? 1ull << 30 : 1ull << 32;
    uint64_t base = s.acc / g * g;
    if (!(r >> 47)) { // up
        uint64_t dist = base + g - s.acc;
        return (dist + r - 1) / r;
    }
    uint64_t mag = ((~r) & kMask48) + 1;
    return (s.acc - base) / mag + 1;
}

uint64_t StepgenBank::sg_horizon(const Sg &s) const
{
    if (s.out != out_d(s))
        return 0;
    uint64_t h = kForever;
    bool neg = s.rate >> 31;
    if (s.pulse) {
        h = s.width_cnt;
    } else if (neg != s.dir) {
        h = s.hold_cnt; // dir_change on the edge after hold runs out
    }
    uint64_t m = ticks_to_cross(s);
    if (m != kForever)
        h = std::min(h, Dds::edges_for(tick_, phase_, master_, 32, m - 1));
    return h;
}

uint64_t StepgenBank::horizon() const
{
    uint64_t h = kForever;
    for (const Sg &s : sg_) {
        h = std::min(h, sg_horizon(s));
        if (h == 0)
            break;
    }
    return h;
}

void StepgenBank::skip(uint64_t n)
{
    if (n == 0)
        return;
    uint64_t k = Dds::ticks(tick_, phase_, master_, 32, n);
    for (Sg &s : sg_) {
        s.acc = (s.acc + k * sext48(rate_eff(s))) & kMask48;
        uint16_t dn = static_cast<uint16_t>(std::min<uint64_t>(n, 0x3fff));
        if (s.pulse) {
            s.width_cnt = static_cast<uint16_t>(s.width_cnt - n);
        } else {
            s.idle_cnt = s.idle_cnt > dn ? static_cast<uint16_t>(s.idle_cnt - dn) : 0;
            s.hold_cnt = s.hold_cnt > dn ? static_cast<uint16_t>(s.hold_cnt - dn) : 0;
        }
        s.setup_cnt = s.setup_cnt > dn ? static_cast<uint16_t>(s.setup_cnt - dn) : 0;
    }
    Dds::advance(tick_, phase_, master_, 32, n);
}

} // namespace vb::fast
