// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_pwm.cpp - the PWMGen bank model (see fast_pwm.h).
#include "fast_pwm.h"

#include <algorithm>

namespace vb::fast {

PwmBank::PwmBank(uint16_t base, uint32_t instances)
    : page_(static_cast<uint8_t>(base >> 8)), num_(instances),
      nenable_(instances >= 32 ? 0xffffffffu : (1u << instances) - 1), inst_(instances)
{
    for (Cfg *c : {&reg_, &xfer_, &cfg_}) {
        c->val.assign(instances, 0);
        c->mode.assign(instances, 0);
    }
    nenable_ = 0; // registers start at 0 until the reset
}

uint32_t PwmBank::read(uint16_t addr) const
{
    uint8_t page = static_cast<uint8_t>(addr >> 8);
    uint8_t off = static_cast<uint8_t>(page - page_);
    if (page >= page_ && off == 4 && ((addr >> 2) & 63) == 0)
        return enable_;
    return 0;
}

void PwmBank::low_edge(const Bus &b, bool rst, bool ack_h_pre)
{
    h_valid_ = false;
    bool ack_s = ack2_;
    ack2_ = ack1_;
    ack1_ = ack_h_pre;
    uint32_t all = num_ >= 32 ? 0xffffffffu : (1u << num_) - 1;
    if (rst) {
        for (uint32_t i = 0; i < num_; i++) {
            reg_.val[i] = 0;
            reg_.mode[i] = 0;
            xfer_.val[i] = 0;
            xfer_.mode[i] = 0;
        }
        reg_.pwmrate = reg_.pdmrate = xfer_.pwmrate = xfer_.pdmrate = 0;
        enable_ = 0;
        nenable_ = all;
        dirty_ = false;
        busy_ = true;
        req_ = false;
        return;
    }
    uint8_t page = b.page();
    uint8_t off = static_cast<uint8_t>(page - page_);
    uint32_t inst = b.inst();
    bool in_range = page >= page_ && off < 5;
    bool inst_ok = inst < num_;
    bool wr_val = b.we && in_range && inst_ok && off == 0;
    bool wr_mode = b.we && in_range && inst_ok && off == 1;
    bool wr_pwmr = b.we && in_range && inst == 0 && off == 2;
    bool wr_pdmr = b.we && in_range && inst == 0 && off == 3;
    bool wr_en = b.we && in_range && inst == 0 && off == 4;
    bool start = dirty_ && !busy_;
    if (start)
        xfer_ = reg_;
    if (wr_val)
        reg_.val[inst] = static_cast<uint16_t>(((b.wdata >> 31) << 12) | ((b.wdata >> 16) & 0xfff));
    if (wr_mode)
        reg_.mode[inst] = b.wdata & 63;
    if (wr_pwmr)
        reg_.pwmrate = static_cast<uint16_t>(b.wdata);
    if (wr_pdmr)
        reg_.pdmrate = static_cast<uint16_t>(b.wdata);
    nenable_ = ~enable_ & all;
    if (wr_en)
        enable_ = b.wdata & all;
    if (start) {
        req_ = !req_;
        busy_ = true;
    } else if (busy_ && ack_s == req_) {
        busy_ = false;
    }
    dirty_ = (dirty_ && !start) || wr_val || wr_mode || wr_pwmr || wr_pdmr;
}

uint16_t PwmBank::span(uint8_t mode)
{
    static const uint16_t s[8] = {0x1ff, 0x3ff, 0x7ff, 0xfff, 0x3ff, 0x7ff, 0xfff, 0x1fff};
    return s[mode & 7];
}

bool PwmBank::cmp_lt(uint16_t ref, uint8_t mode, uint16_t act)
{
    uint16_t sp = span(mode);
    uint16_t m = ref & sp;
    uint16_t half = sp >> 1;
    uint16_t tri = m > half ? static_cast<uint16_t>(sp - m) : m;
    uint16_t c = (mode & 4) ? tri : m;
    return c < (act & 0xfff);
}

void PwmBank::out_map(uint8_t mode, bool pwm, bool dir, bool pdm, bool &o0, bool &o1)
{
    switch ((mode >> 3) & 3) {
    case 0: o0 = pwm; o1 = dir; break;
    case 1: o0 = dir; o1 = pwm; break;
    case 2: o0 = pwm && dir; o1 = pwm && !dir; break;
    default: o0 = pdm; o1 = dir; break;
    }
}

bool PwmBank::high_edge(bool rst)
{
    h_valid_ = false;
    bool rst_h = r2_;
    bool changed = false;
    r2_ = r1_;
    r1_ = rst;
    if (rst_h) {
        q1_ = q2_ = false;
        ack_h_ = false;
        for (uint32_t i = 0; i < num_; i++) {
            cfg_.val[i] = 0;
            cfg_.mode[i] = 0;
            changed = changed || inst_[i].out0 || inst_[i].out1;
            inst_[i] = Inst{};
        }
        cfg_.pwmrate = cfg_.pdmrate = 0;
        pwm_phase_ = pdm_phase_ = 0;
        pwm_tick_ = pdm_tick_ = false;
        ref_ = 0;
        return changed;
    }
    bool req_s = q2_;
    q2_ = q1_;
    q1_ = req_;
    const Cfg pre_rates{{}, {}, cfg_.pwmrate, cfg_.pdmrate};
    for (uint32_t i = 0; i < num_; i++) {
        Inst &s = inst_[i];
        uint8_t mode = cfg_.mode[i];
        uint16_t sp = span(mode);
        bool cycle_start = pwm_tick_ && (ref_ & sp) == sp;
        bool dbuf = mode & 32;
        uint32_t pdm_sum = static_cast<uint32_t>(s.pdm_acc) + (s.act & 0xfff);
        Inst n = s;
        if (!dbuf || cycle_start)
            n.act = cfg_.val[i];
        n.pwm = cmp_lt(ref_, mode, s.act);
        n.dir = (s.act >> 12) & 1;
        if (pdm_tick_) {
            n.pdm_acc = pdm_sum & 0xfff;
            n.pdm = pdm_sum >> 12;
        }
        out_map(mode, s.pwm, s.dir, s.pdm, n.out0, n.out1);
        changed = changed || n.out0 != s.out0 || n.out1 != s.out1;
        s = n;
    }
    if (req_s != ack_h_) {
        cfg_ = xfer_;
        ack_h_ = req_s;
    }
    uint32_t ps = static_cast<uint32_t>(pwm_phase_) + pre_rates.pwmrate;
    uint32_t ds = static_cast<uint32_t>(pdm_phase_) + pre_rates.pdmrate;
    if (pwm_tick_)
        ref_ = (ref_ + 1) & 0x1fff;
    pwm_phase_ = ps & 0xffff;
    pdm_phase_ = ds & 0xffff;
    pwm_tick_ = ps >> 16;
    pdm_tick_ = ds >> 16;
    return changed;
}

// Ref increments until instance i's comparator output changes (kForever:
// never while the configuration stays).
uint64_t PwmBank::ticks_to_change(uint32_t i) const
{
    uint8_t mode = cfg_.mode[i];
    uint16_t a = inst_[i].act & 0xfff;
    uint16_t sp = span(mode);
    uint32_t period = static_cast<uint32_t>(sp) + 1;
    uint32_t c = ref_ & sp;
    uint32_t pts[2];
    int np = 0;
    if (mode & 4) {
        uint16_t half = sp >> 1;
        if (a >= 1 && a <= half) {
            pts[np++] = a;
            pts[np++] = sp - a + 1;
        }
    } else if (a >= 1 && a <= sp) {
        pts[np++] = a;
        pts[np++] = 0;
    }
    uint64_t d = kForever;
    for (int k = 0; k < np; k++)
        d = std::min<uint64_t>(d, (pts[k] + 2 * period - c - 1) % period + 1);
    return d;
}

uint64_t PwmBank::horizon_high() const
{
    if (!h_valid_) {
        h_ = compute_horizon();
        h_valid_ = true;
    }
    return h_;
}

uint64_t PwmBank::compute_horizon() const
{
    // handshake and reset settled, nothing pending on either side
    if (r1_ || r2_ || dirty_ || busy_ || req_ != ack_h_ || q1_ != req_ || q2_ != req_ ||
        ack1_ != ack_h_ || ack2_ != ack_h_)
        return 0;
    uint32_t all = num_ >= 32 ? 0xffffffffu : (1u << num_) - 1;
    if (nenable_ != (~enable_ & all))
        return 0;
    uint64_t ref_ticks = kForever; // pwm ticks the window may contain before the last edge
    uint64_t h = kForever;
    bool pdm_out = false;
    for (uint32_t i = 0; i < num_; i++) {
        const Inst &s = inst_[i];
        uint8_t mode = cfg_.mode[i];
        bool dbuf = mode & 32;
        if ((!dbuf && s.act != cfg_.val[i]) || s.dir != ((s.act >> 12) & 1) ||
            s.pwm != cmp_lt(ref_, mode, s.act))
            return 0;
        bool o0, o1;
        out_map(mode, s.pwm, s.dir, s.pdm, o0, o1);
        if (o0 != s.out0 || o1 != s.out1)
            return 0;
        if (((mode >> 3) & 3) == 3)
            pdm_out = true;
        uint64_t d = ticks_to_change(i);
        if (d != kForever)
            ref_ticks = std::min(ref_ticks, d - 1);
        if (dbuf && s.act != cfg_.val[i]) {
            uint16_t sp = span(mode);
            uint64_t dcs = ((sp - (ref_ & sp)) & sp) + 1;
            h = std::min(h, Dds::edges_for(pwm_tick_, pwm_phase_, cfg_.pwmrate, 16, dcs - 1));
        }
    }
    if (ref_ticks != kForever)
        h = std::min(h, Dds::edges_for(pwm_tick_, pwm_phase_, cfg_.pwmrate, 16, ref_ticks));
    if (pdm_out)
        h = std::min(h, Dds::edges_for(pdm_tick_, pdm_phase_, cfg_.pdmrate, 16, 0));
    return h;
}

void PwmBank::skip_high(uint64_t n)
{
    if (n == 0)
        return;
    if (h_valid_)
        h_ = h_ == kForever ? h_ : h_ - n;
    uint64_t k = Dds::ticks(pwm_tick_, pwm_phase_, cfg_.pwmrate, 16, n);
    uint64_t kp = Dds::ticks(pdm_tick_, pdm_phase_, cfg_.pdmrate, 16, n);
    ref_ = static_cast<uint16_t>((ref_ + k) & 0x1fff);
    if (kp) {
        for (Inst &s : inst_) {
            uint64_t a = s.act & 0xfff;
            uint64_t before_last = (s.pdm_acc + (kp - 1) % 4096 * a) & 0xfff;
            s.pdm = ((before_last + a) >> 12) & 1;
            s.pdm_acc = static_cast<uint16_t>((before_last + a) & 0xfff);
        }
    }
    Dds::advance(pwm_tick_, pwm_phase_, cfg_.pwmrate, 16, n);
    Dds::advance(pdm_tick_, pdm_phase_, cfg_.pdmrate, 16, n);
}

} // namespace vb::fast
