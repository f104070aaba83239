// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_basic.cpp - DDS arithmetic, IDROM, watchdog, LED and IOPort models
// (hm2_idrom.v, hm2_watchdog.v, hm2_led.v, hm2_ioport_bank.v).
#include <cstring>

#include "fast_modules.h"

namespace vb::fast {

using u128 = unsigned __int128;

// ---- Dds ------------------------------------------------------------------------
// The consumer sees the tick register before each edge: before edge 1 the
// present one, before edge j the carry of edge j-1.  Over the next n edges
// the carries of edges 1..n-1 add up to floor((phase + (n-1)*rate) / 2^bits).
uint64_t Dds::ticks(bool tick, uint64_t phase, uint64_t rate, unsigned bits, uint64_t n)
{
    if (n == 0)
        return 0;
    u128 sum = static_cast<u128>(phase) + static_cast<u128>(n - 1) * rate;
    return (tick ? 1 : 0) + static_cast<uint64_t>(sum >> bits);
}

uint64_t Dds::edges_for(bool tick, uint64_t phase, uint64_t rate, unsigned bits, uint64_t k)
{
    uint64_t t0 = tick ? 1 : 0;
    if (k < t0)
        return 0;
    if (rate == 0 || k == kForever)
        return kForever;
    u128 x = (static_cast<u128>(k - t0 + 1) << bits) - phase;
    u128 n = (x + rate - 1) / rate;
    return n >= kForever ? kForever - 1 : static_cast<uint64_t>(n);
}

void Dds::advance(bool &tick, uint64_t &phase, uint64_t rate, unsigned bits, uint64_t n)
{
    if (n == 0)
        return;
    u128 prev = static_cast<u128>(phase) + static_cast<u128>(n - 1) * rate;
    u128 total = prev + rate;
    tick = (total >> bits) != (prev >> bits);
    phase = static_cast<uint64_t>(total & ((static_cast<u128>(1) << bits) - 1));
}

// ---- IDROM ------------------------------------------------------------------------
Idrom::Idrom(const uint32_t *words) { std::memcpy(mem_, words, sizeof mem_); }

uint32_t Idrom::read(uint16_t addr) const
{
    uint8_t page = static_cast<uint8_t>(addr >> 8);
    if ((page >> 2) == 1)
        return mem_[(addr >> 2) & 0xff];
    if (page == 0x01) {
        static const uint32_t id[4] = {0x55AACAFEu, 0x54534F48u, 0x32544F4Du, 0x00000400u};
        return id[(addr >> 2) & 3];
    }
    if (page == 0x08 && ((addr >> 2) & 63) == 0)
        return wen_ ? 1u : 0u;
    return 0;
}

void Idrom::edge(const Bus &b, bool rst)
{
    // The RAM write is not under reset; the enable register is.
    if (b.we && (b.page() >> 2) == 1 && wen_)
        mem_[(b.addr >> 2) & 0xff] = b.wdata;
    if (rst)
        wen_ = false;
    else if (b.we && b.page() == 0x08 && b.inst() == 0)
        wen_ = b.wdata & 1;
}

// ---- Watchdog ---------------------------------------------------------------------
uint32_t Watchdog::read(uint16_t addr) const
{
    uint8_t page = static_cast<uint8_t>(addr >> 8);
    if (((addr >> 2) & 63) != 0)
        return 0;
    if (page == page_)
        return timer_;
    if (page == static_cast<uint8_t>(page_ + 1))
        return status_ ? 1u : 0u;
    return 0;
}

void Watchdog::edge(const Bus &b, bool rst)
{
    if (rst) {
        timer_ = reload_ = 0;
        status_ = under_ = bite_ = false;
        return;
    }
    bool inst0 = b.inst() == 0;
    bool wr_timer = b.we && inst0 && b.page() == page_;
    bool wr_status = b.we && inst0 && b.page() == static_cast<uint8_t>(page_ + 1);
    bool wr_pet = b.we && inst0 && b.page() == static_cast<uint8_t>(page_ + 2) &&
                  (b.wdata >> 24) == 0x5A;
    bool counting = !(timer_ >> 31);
    bool bite_d = !wr_timer && !wr_pet && counting && timer_ == 0;
    if (wr_timer) {
        timer_ = b.wdata;
        reload_ = b.wdata;
    } else if (wr_pet) {
        timer_ = reload_;
    } else if (counting) {
        timer_--;
    }
    bite_ = under_;
    under_ = bite_d;
    if (bite_d)
        status_ = true;
    else if (wr_status)
        status_ = b.wdata & 1;
}

uint64_t Watchdog::horizon() const
{
    if (under_ || bite_)
        return 0;
    if (timer_ >> 31)
        return kForever;
    return timer_; // the edge after these bites
}

// ---- LED ----------------------------------------------------------------------------
void Led::edge(const Bus &b, bool rst)
{
    if (rst)
        led_ = 0;
    else if (b.we && b.page() == page_ && b.inst() == 0)
        led_ = b.wdata;
}

// ---- IOPort ---------------------------------------------------------------------------
IoPort::IoPort(uint16_t base, uint32_t ports, uint32_t width)
    : page_(static_cast<uint8_t>(base >> 8)), ports_(ports), width_(width),
      mask_(width >= 32 ? 0xffffffffu : (1u << width) - 1), data_(ports), ddr_(ports),
      alt_(ports), od_(ports), inv_(ports), s1_(ports), s2_(ports)
{
}

uint32_t IoPort::port_bits(const uint32_t *v, uint32_t port) const
{
    uint32_t first = port * width_;
    uint32_t w = first >> 5, sh = first & 31;
    uint64_t two = v[w];
    if (sh + width_ > 32)
        two |= static_cast<uint64_t>(v[w + 1]) << 32;
    return static_cast<uint32_t>(two >> sh) & mask_;
}

uint32_t IoPort::read(uint16_t addr) const
{
    uint8_t page = static_cast<uint8_t>(addr >> 8);
    uint8_t off = static_cast<uint8_t>(page - page_);
    uint32_t inst = (addr >> 2) & 63;
    if (page < page_ || off >= 5 || inst >= ports_)
        return 0;
    if (off == 0)
        return s2_[inst];
    if (off == 1)
        return ddr_[inst];
    return 0;
}

void IoPort::edge(const Bus &b, bool rst, bool bite, const uint32_t *in)
{
    if (rst) {
        for (uint32_t p = 0; p < ports_; p++) {
            data_[p] = ddr_[p] = alt_[p] = od_[p] = inv_[p] = 0;
            s1_[p] = s2_[p] = mask_;
        }
        return;
    }
    uint8_t page = b.page();
    uint8_t off = static_cast<uint8_t>(page - page_);
    uint32_t inst = b.inst();
    if (b.we && page >= page_ && off < 5 && inst < ports_) {
        uint32_t v = b.wdata & mask_;
        switch (off) {
        case 0: data_[inst] = v; break;
        case 1: ddr_[inst] = v; break;
        case 2: alt_[inst] = v; break;
        case 3: od_[inst] = v; break;
        default: inv_[inst] = v; break;
        }
    }
    if (bite)
        for (uint32_t p = 0; p < ports_; p++)
            ddr_[p] = od_[p] = 0;
    for (uint32_t p = 0; p < ports_; p++) {
        s2_[p] = s1_[p];
        s1_[p] = port_bits(in, p);
    }
}

void IoPort::outputs(const uint32_t *alt, uint32_t *out, uint32_t *oe) const
{
    uint32_t words = (ports_ * width_ + 31) / 32;
    std::memset(out, 0, words * 4);
    std::memset(oe, 0, words * 4);
    for (uint32_t p = 0; p < ports_; p++) {
        uint32_t a = port_bits(alt, p);
        uint32_t d = ((alt_[p] & a) | (~alt_[p] & data_[p])) ^ inv_[p];
        uint32_t o = d & ~od_[p] & mask_;
        uint32_t e = ((od_[p] & ~d) | (~od_[p] & ddr_[p])) & mask_;
        uint32_t first = p * width_;
        uint32_t w = first >> 5, sh = first & 31;
        out[w] |= o << sh;
        oe[w] |= e << sh;
        if (sh + width_ > 32) {
            out[w + 1] |= o >> (32 - sh);
            oe[w + 1] |= e >> (32 - sh);
        }
    }
}

uint64_t IoPort::horizon(const uint32_t *in) const
{
    for (uint32_t p = 0; p < ports_; p++) {
        uint32_t v = port_bits(in, p);
        if (s1_[p] != v || s2_[p] != v)
            return 0;
    }
    return kForever;
}

} // namespace vb::fast
