// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_model.cpp - the fast hm2 board model (see fast_model.h).
#include "fast_model.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>

#include "fast_config.h"
#include "fast_encoder.h"
#include "fast_modules.h"
#include "fast_pwm.h"
#include "fast_stepgen.h"

namespace vb::fast {

namespace {

// Where an I/O pin's module output comes from.
struct OutSrc {
    uint32_t pin;
    uint8_t tag;   // kTagStepGen / kTagPwmGen
    uint8_t unit;
    uint8_t which; // StepGen: output k; PWMGen: 0 Out0, 1 Out1, 2 NotEnable
};

class FastModel final : public LbModelBase {
  public:
    static constexpr int kResetCycles = 4;   // as LbModel
    static constexpr int kStartupCycles = 4; // as LbModel

    FastModel(const FwInfo &info, const Config &cfg, PinBank &pins, uint64_t start)
        : pins_(pins), th_(1000000000ull / info.clock_high_hz),
          ratio_((info.clock_high_hz + info.clock_low_hz / 2) / info.clock_low_hz),
          idrom_(cfg.idrom), wd_(cfg.find(kTagWatchdog)->base),
          io_(cfg.find(kTagIoPort)->base, cfg.io_ports, cfg.port_width),
          out_(pins.words()), oe_(pins.words()), alt_(pins.words())
    {
        if (!info.uses_clock_high) {
            th_ *= ratio_;
            ratio_ = 1;
        }
        build(cfg);
        next_edge_ = (start + th_ - 1) / th_ * th_;
        now_ = start;
        rst_ = true;
        for (int i = 0; i < kResetCycles; i++)
            low_cycle();
        rst_ = false;
        for (int i = 0; i < kStartupCycles; i++)
            low_cycle();
    }

    uint64_t now_ns() const override { return now_; }

    void run_until(uint64_t t) override
    {
        while (next_edge_ <= t) {
            if (k_ % ratio_ == 0 && try_skip(t))
                continue;
            edge();
        }
        if (t > now_)
            now_ = t;
    }

    int read(const vb_xfer *x, size_t n, std::vector<uint8_t> &out, std::string &err) override
    {
        std::vector<uint32_t> addrs;
        for (size_t i = 0; i < n; i++)
            for (uint32_t off = 0; off < x[i].size; off += 4)
                addrs.push_back(x[i].addr + off);
        size_t base = out.size();
        out.resize(base + addrs.size() * 4);
        for (size_t e = 0; e <= addrs.size(); e++) {
            if (e < addrs.size()) {
                lb_rd_ = true;
                lb_addr_ = static_cast<uint16_t>(addrs[e]);
            } else {
                lb_rd_ = false;
            }
            low_cycle();
            if (e == 0)
                continue;
            if (!rvalid_) {
                lb_rd_ = false;
                out.resize(base);
                err = "local bus: read got no lb_rvalid from the fast model";
                return -EIO;
            }
            std::memcpy(&out[base + (e - 1) * 4], &rdata_, 4);
        }
        return 0;
    }

    void write(const vb_xfer *x, size_t n, const uint8_t *data) override
    {
        for (size_t i = 0; i < n; i++)
            for (uint32_t off = 0; off < x[i].size; off += 4) {
                std::memcpy(&lb_wdata_, data, 4);
                data += 4;
                lb_wr_ = true;
                lb_addr_ = static_cast<uint16_t>(x[i].addr + off);
                low_cycle();
            }
        lb_wr_ = false;
        low_cycle();
        low_cycle();
    }

    int dump(bool on, const std::string &path, std::string &err) override
    {
        (void)path;
        if (!on)
            return 0;
        err = "dump: the fast model has no waveforms; run the board with --model rtl";
        return -ENOTSUP;
    }

    FastStats stats() const { return stats_; }

  private:
    void build(const Config &cfg)
    {
        std::vector<std::array<int, 5>> enc_pins;
        const ModuleDesc *enc = cfg.find(kTagEncoder);
        const ModuleDesc *sg = cfg.find(kTagStepGen);
        const ModuleDesc *pwm = cfg.find(kTagPwmGen);
        const ModuleDesc *led = cfg.find(kTagLed);
        if (enc)
            enc_pins.assign(enc->instances, {-1, -1, -1, -1, -1});
        for (uint32_t p = 0; p < cfg.io_width; p++) {
            const PinDesc &d = cfg.pins[p];
            if (enc && d.sec_tag == kTagEncoder && d.sec_unit < enc->instances &&
                d.sec_pin >= 1 && d.sec_pin <= 5)
                enc_pins[d.sec_unit][d.sec_pin - 1] = static_cast<int>(p);
            if (!(d.sec_pin & 0x80))
                continue;
            uint8_t k = static_cast<uint8_t>((d.sec_pin & 0x7f) - 1);
            if (sg && d.sec_tag == kTagStepGen && d.sec_unit < sg->instances &&
                k < StepgenBank::kTableWidth)
                srcs_.push_back({p, kTagStepGen, d.sec_unit, k});
            if (pwm && d.sec_tag == kTagPwmGen && d.sec_unit < pwm->instances && k < 3)
                srcs_.push_back({p, kTagPwmGen, d.sec_unit, k});
        }
        if (enc)
            enc_ = std::make_unique<EncoderBank>(enc->base, cfg.clock_low_hz, enc_pins);
        if (sg)
            sg_ = std::make_unique<StepgenBank>(sg->base, sg->instances);
        if (pwm)
            pwm_ = std::make_unique<PwmBank>(pwm->base, pwm->instances);
        if (led)
            led_ = std::make_unique<Led>(led->base);
    }

    // One ClockLow edge of every ClockLow-domain module.
    void low_edge(const uint32_t *in, bool ack_h_pre, bool pwm_idle)
    {
        if (rst_) {
            rdata_ = 0;
            rvalid_ = false;
        } else {
            if (bus_.re) {
                uint16_t a = bus_.addr;
                uint32_t v = idrom_.read(a) | wd_.read(a) | io_.read(a);
                if (enc_)
                    v |= enc_->read(a);
                if (sg_)
                    v |= sg_->read(a);
                if (pwm_)
                    v |= pwm_->read(a);
                rdata_ = v;
            }
            rvalid_ = bus_.re;
        }
        bool bite = wd_.bite();
        idrom_.edge(bus_, rst_);
        wd_.edge(bus_, rst_);
        io_.edge(bus_, rst_, bite, in);
        if (led_)
            led_->edge(bus_, rst_);
        if (enc_)
            enc_->edge(bus_, rst_, in);
        if (sg_)
            sg_->edge(bus_, rst_);
        if (pwm_ && !pwm_idle)
            pwm_->low_edge(bus_, rst_, ack_h_pre);
        if (rst_)
            bus_ = Bus{};
        else
            bus_ = Bus{lb_addr_, lb_wdata_, lb_wr_, lb_rd_};
    }

    void outputs()
    {
        std::fill(alt_.begin(), alt_.end(), 0u);
        for (const OutSrc &s : srcs_) {
            bool v;
            if (s.tag == kTagStepGen)
                v = sg_->out(s.unit, s.which);
            else
                v = s.which == 0 ? pwm_->out0(s.unit)
                    : s.which == 1 ? pwm_->out1(s.unit) : pwm_->nenable(s.unit);
            if (v)
                alt_[s.pin >> 5] |= 1u << (s.pin & 31);
        }
        io_.outputs(alt_.data(), out_.data(), oe_.data());
    }

    // One ClockHigh edge (and the ClockLow edge on every ratio-th).
    void edge()
    {
        uint64_t t = next_edge_;
        if (pins_.next_event_ns() <= t)
            pins_.run_events(t);
        const uint32_t *in = pins_.inputs();
        bool low = k_ % ratio_ == 0;
        k_++;
        next_edge_ += th_;
        now_ = t;
        if (!low && (!pwm_ || pwm_->horizon_high() > 0)) {
            // a ClockHigh-only edge that changes no PWM output: closed form
            if (pwm_)
                pwm_->skip_high(1);
            stats_.skipped++;
            return;
        }
        bool ack_pre = pwm_ ? pwm_->ack_h() : false;
        bool changed = low;
        bool pwm_idle = pwm_ && low && !rst_ && pwm_->idle_low_edge_ok(bus_);
        if (pwm_idle)
            pwm_->skip_high(1);
        else if (pwm_)
            changed = pwm_->high_edge(rst_) || changed;
        if (low)
            low_edge(in, ack_pre, pwm_idle);
        if (changed) {
            outputs();
            pins_.set_fpga(out_.data(), oe_.data(), t);
        }
        stats_.stepped++;
    }

    void low_cycle()
    {
        for (;;) {
            bool low = k_ % ratio_ == 0;
            edge();
            if (low)
                break;
        }
    }

    // Let whole ClockLow cycles pass in closed form (at a ClockLow edge, bus
    // idle); false when not one may.
    bool try_skip(uint64_t t)
    {
        if (rst_ || bus_.we || bus_.re || lb_wr_ || lb_rd_)
            return false;
        uint64_t limit = t;
        uint64_t ev = pins_.next_event_ns();
        if (ev != PinBank::kNever) {
            if (ev <= next_edge_)
                return false;
            limit = std::min(limit, ev - 1);
        }
        uint64_t edges = (limit - next_edge_) / th_ + 1; // ClockHigh edges before the limit
        uint64_t n = edges / ratio_;
        if (n == 0)
            return false;
        const uint32_t *in = pins_.inputs();
        n = std::min(n, wd_.horizon());
        if (n)
            n = std::min(n, io_.horizon(in));
        if (n && enc_)
            n = std::min(n, enc_->horizon(in));
        if (n && sg_)
            n = std::min(n, sg_->horizon());
        if (n && pwm_) {
            uint64_t h = pwm_->horizon_high();
            n = std::min(n, h == kForever ? h : h / ratio_);
        }
        if (n == 0)
            return false;
        wd_.skip(n);
        if (enc_)
            enc_->skip(n);
        if (sg_)
            sg_->skip(n);
        if (pwm_)
            pwm_->skip_high(n * ratio_);
        rvalid_ = false;
        bus_ = Bus{lb_addr_, lb_wdata_, false, false};
        k_ += n * ratio_;
        next_edge_ += n * ratio_ * th_;
        now_ = next_edge_ - th_;
        stats_.skipped += n * ratio_;
        return true;
    }

    PinBank &pins_;
    uint64_t th_, ratio_;
    Idrom idrom_;
    Watchdog wd_;
    IoPort io_;
    std::unique_ptr<Led> led_;
    std::unique_ptr<EncoderBank> enc_;
    std::unique_ptr<StepgenBank> sg_;
    std::unique_ptr<PwmBank> pwm_;
    std::vector<OutSrc> srcs_;
    std::vector<uint32_t> out_, oe_, alt_;
    // local bus: the host's inputs and the registered bus
    uint16_t lb_addr_ = 0;
    uint32_t lb_wdata_ = 0;
    bool lb_wr_ = false, lb_rd_ = false;
    Bus bus_;
    uint32_t rdata_ = 0;
    bool rvalid_ = false;
    bool rst_ = false;
    uint64_t next_edge_ = 0, now_ = 0, k_ = 0;
    FastStats stats_;
};

} // namespace

std::string fast_coverage(const uint32_t *idrom)
{
    Config cfg;
    std::string err;
    return parse_config(idrom, cfg, err) < 0 ? err : "";
}

std::unique_ptr<LbModelBase> make_fast_model(const FwInfo &info, const uint32_t *idrom,
                                             PinBank &pins, uint64_t start, std::string &err)
{
    Config cfg;
    if (parse_config(idrom, cfg, err) < 0)
        return nullptr;
    if (cfg.io_width != info.io_width || cfg.io_width > pins.size()) {
        err = "fast model: the IDROM of " + std::string(info.firmware) + " has IOWidth " +
              std::to_string(cfg.io_width) + " but the firmware has " +
              std::to_string(info.io_width) + " I/O pins";
        return nullptr;
    }
    return std::make_unique<FastModel>(info, cfg, pins, start);
}

FastStats fast_stats(const LbModelBase &m)
{
    const auto *f = dynamic_cast<const FastModel *>(&m);
    return f ? f->stats() : FastStats{};
}

} // namespace vb::fast
