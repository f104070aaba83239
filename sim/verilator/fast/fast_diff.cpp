// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_diff.cpp - vboard-fastdiff: differential test of the fast model
// against the Verilated firmware (the reference).
//
//   vboard-fastdiff --board 5i20 --firmware SVST8_4 --module NAME --ops N [--seed S]
//                   [--long NS]   (the longest time advance, default 2 ms)
//
// Two pin banks, one per model, get the same stimulus: bus writes and
// burst reads of the module's registers (random, after a directed set-up
// that routes the module's outputs to the pins), board time advanced by
// random amounts, pins driven and released, quadrature sources started and
// stopped, and a stimulus agent that toggles input pins at random board
// times.  Every read is compared word by word, and after every operation
// the two pin histories (every level change of every pin, with its board
// time) are compared.  The first difference fails the run with the
// operation, the board time and the ClockLow cycle where the models part.
// NAME: idrom, ioport, watchdog, encoder, stepgen, pwmgen, led, all.
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "fast_config.h"
#include "fast_idroms.h"
#include "fast_model.h"
#include "localbus.h"

namespace {

using vb::PinBank;

struct Change {
    uint32_t pin;
    bool level;
    uint64_t t;
    bool operator==(const Change &o) const { return pin == o.pin && level == o.level && t == o.t; }
};

// Watches every pin; owns the stimulus pins and toggles them at
// pseudo-random board times (the same in both banks: the times come from
// the agent's own generator, advanced only by its own events).
class Agent final : public vb::PinAgent {
  public:
    Agent(PinBank &bank, std::vector<uint32_t> stim, uint32_t seed, uint64_t mean_gap)
        : bank_(bank), stim_(std::move(stim)), rng_(seed), mean_(mean_gap)
    {
        for (uint32_t p = 0; p < bank.size(); p++)
            bank.watch(p);
        for (uint32_t p : stim_)
            bank.own(p, true, 0);
        next_ = stim_.empty() ? PinBank::kNever : gap();
        bank.set_agent(this);
    }
    uint64_t next_event() const override { return next_; }
    void run(uint64_t t) override
    {
        while (next_ <= t) {
            uint32_t p = stim_[rng_() % stim_.size()];
            bank_.agent_set(p, !bank_.level(p), next_);
            next_ += gap();
        }
    }
    void on_pin(uint32_t pin, bool level, uint64_t t) override { log.push_back({pin, level, t}); }
    std::vector<Change> log;

  private:
    uint64_t gap() { return 1 + rng_() % (2 * mean_); }
    PinBank &bank_;
    std::vector<uint32_t> stim_;
    std::mt19937 rng_;
    uint64_t mean_;
    uint64_t next_ = PinBank::kNever;
};

struct Side {
    std::unique_ptr<PinBank> pins;
    std::unique_ptr<Agent> agent;
    std::unique_ptr<vb::LbModelBase> m;
};

struct Range {
    uint16_t base;
    uint8_t regs, instances;
};

[[noreturn]] void die(const std::string &msg)
{
    std::fprintf(stderr, "vboard-fastdiff: %s\n", msg.c_str());
    std::exit(1);
}

class Diff {
  public:
    Diff(const vb::LbEntry &e, const uint32_t *idrom, const std::string &module, uint32_t seed)
        : info_(*e.info), rng_(seed), module_(module)
    {
        std::string err;
        if (vb::fast::parse_config(idrom, cfg_, err) < 0)
            die(err);
        tl_ = 1000000000ull / info_.clock_low_hz;
        std::vector<uint32_t> stim = stim_pins();
        for (Side *s : {&rtl_, &fast_}) {
            s->pins = std::make_unique<PinBank>(info_.io_width);
            s->agent = std::make_unique<Agent>(*s->pins, stim, seed ^ 0x5eed, 700);
        }
        rtl_.m = e.make(info_, *rtl_.pins, 0);
        fast_.m = vb::fast::make_fast_model(info_, idrom, *fast_.pins, 0, err);
        if (!fast_.m)
            die(err);
        collect_ranges();
        if (ranges_.empty())
            die("firmware " + std::string(info_.firmware) + " has no module '" + module_ + "'");
    }

    void run(uint64_t ops)
    {
        setup();
        for (op_ = 0; op_ < ops; op_++) {
            unsigned r = rng_() % 100;
            if (r < 30)
                random_write();
            else if (r < 55)
                random_read();
            else if (r < 90)
                advance();
            else if (r < 95)
                random_drive();
            else
                random_quad();
            compare_logs();
        }
        std::printf("vboard-fastdiff: %s %s module %s: %" PRIu64 " operations, %" PRIu64
                    " reads, %zu pin edges, board time %.3f ms: models agree\n",
                    info_.board, info_.firmware, module_.c_str(), ops, reads_,
                    rtl_.agent->log.size(), static_cast<double>(fast_.m->now_ns()) / 1e6);
        vb::fast::FastStats st = vb::fast::fast_stats(*fast_.m);
        std::printf("vboard-fastdiff: fast model edges stepped %" PRIu64 ", skipped %" PRIu64 "\n",
                    st.stepped, st.skipped);
    }

  private:
    bool wants(uint8_t tag) const
    {
        if (module_ == "all")
            return true;
        if (module_ == "idrom")
            return false;
        static const struct {
            const char *name;
            uint8_t tag;
        } names[] = {{"ioport", vb::fast::kTagIoPort},   {"watchdog", vb::fast::kTagWatchdog},
                     {"encoder", vb::fast::kTagEncoder}, {"stepgen", vb::fast::kTagStepGen},
                     {"pwmgen", vb::fast::kTagPwmGen},   {"led", vb::fast::kTagLed}};
        for (const auto &n : names)
            if (module_ == n.name)
                return tag == n.tag;
        die("unknown module '" + module_ +
            "' (ioport, watchdog, encoder, stepgen, pwmgen, led, all)");
    }

    // Input pins the agent toggles: the module's inputs (encoders) or, for
    // the IOPort, every third pin.
    std::vector<uint32_t> stim_pins() const
    {
        std::vector<uint32_t> v;
        for (uint32_t p = 0; p < cfg_.io_width; p++) {
            const auto &d = cfg_.pins[p];
            bool enc_in = d.sec_tag == vb::fast::kTagEncoder && !(d.sec_pin & 0x80);
            if ((enc_in && (module_ == "encoder" || module_ == "all")) ||
                (module_ == "ioport" && p % 3 == 0))
                v.push_back(p);
        }
        return v;
    }

    void collect_ranges()
    {
        if (module_ == "idrom" || module_ == "all") {
            ranges_.push_back({0x0100, 1, 4});  // ID block
            ranges_.push_back({0x0400, 4, 64}); // IDROM words
            ranges_.push_back({0x0800, 1, 1});  // IDROM write enable
        }
        for (const auto &m : cfg_.modules) {
            if (module_ != "idrom" && wants(m.gtag))
                ranges_.push_back({m.base, m.registers, m.instances});
            if (m.gtag == vb::fast::kTagIoPort)
                io_ = {m.base, m.registers, m.instances};
            if (m.gtag == vb::fast::kTagStepGen)
                sg_base_ = m.base;
            if (m.gtag == vb::fast::kTagPwmGen)
                pwm_base_ = m.base;
        }
    }

    void write1(uint32_t addr, uint32_t v)
    {
        vb_xfer x{addr, 4};
        rtl_.m->write(&x, 1, reinterpret_cast<const uint8_t *>(&v));
        fast_.m->write(&x, 1, reinterpret_cast<const uint8_t *>(&v));
    }

    // Route every module output to its pin and make it an output; a
    // watchdog long enough not to bite unless the test wants it to.
    void setup()
    {
        if (module_ != "watchdog" && module_ != "all")
            write1(cfg_.find(vb::fast::kTagWatchdog)->base, 0x7fffffff);
        for (uint32_t p = 0; p < io_.instances; p++) {
            uint32_t outs = 0; // the pins the modules drive
            for (uint32_t b = 0; b < cfg_.port_width; b++)
                if (cfg_.pins[p * cfg_.port_width + b].sec_pin & 0x80)
                    outs |= 1u << b;
            write1(io_.base + 0x200 + 4 * p, 0xffffffff); // alt source
            write1(io_.base + 0x100 + 4 * p, module_ == "ioport" ? 0x00aaaaaa : outs);
        }
        if (sg_base_ && (module_ == "stepgen" || module_ == "all"))
            write1(sg_base_ + 0x900u, 0x80000000u); // master rate: a tick every other clock
        if (pwm_base_ && (module_ == "pwmgen" || module_ == "all"))
            write1(pwm_base_ + 0x200u, 0x4000); // PWM rate
    }

    uint32_t random_data()
    {
        switch (rng_() % 6) {
        case 0: return 0;
        case 1: return rng_() % 16;
        case 2: return rng_() % 4096;
        case 3: return 0xffffffffu - rng_() % 4096;
        case 4: return (rng_() % 2 ? 1u : 0xffffffffu) * (rng_() % 0x100000);
        default: return static_cast<uint32_t>(rng_());
        }
    }

    uint32_t random_addr()
    {
        const Range &r = ranges_[rng_() % ranges_.size()];
        uint32_t reg = rng_() % (r.regs + (rng_() % 8 == 0 ? 1 : 0));
        uint32_t inst = rng_() % (r.instances + (rng_() % 8 == 0 ? 2 : 0));
        return r.base + reg * 0x100 + 4 * inst;
    }

    void random_write()
    {
        uint32_t n = 1 + rng_() % 4;
        std::vector<uint32_t> data;
        std::vector<vb_xfer> x;
        for (uint32_t i = 0; i < n; i++) {
            uint32_t a = random_addr();
            uint32_t v = random_data();
            // the watchdog: mostly long timeouts and pets, sometimes a bite
            if (a == cfg_.find(vb::fast::kTagWatchdog)->base && module_ != "watchdog")
                v = 0x7fffffff;
            x.push_back({a, 4});
            data.push_back(v);
        }
        rtl_.m->write(x.data(), n, reinterpret_cast<const uint8_t *>(data.data()));
        fast_.m->write(x.data(), n, reinterpret_cast<const uint8_t *>(data.data()));
        check_time();
    }

    void random_read()
    {
        uint32_t n = 1 + rng_() % 6;
        std::vector<vb_xfer> x;
        for (uint32_t i = 0; i < n; i++)
            x.push_back({random_addr(), 4});
        std::vector<uint8_t> a, b;
        std::string ea, eb;
        int ra = rtl_.m->read(x.data(), n, a, ea);
        int rb = fast_.m->read(x.data(), n, b, eb);
        if (ra != rb || a != b) {
            for (uint32_t i = 0; i < n && ra == 0 && rb == 0; i++) {
                uint32_t va, vf;
                std::memcpy(&va, &a[4 * i], 4);
                std::memcpy(&vf, &b[4 * i], 4);
                if (va != vf)
                    fail("read of 0x" + hex(x[i].addr, 4) + ": RTL 0x" + hex(va, 8) +
                         ", fast 0x" + hex(vf, 8));
            }
            fail("read: RTL rc " + std::to_string(ra) + " (" + ea + "), fast rc " +
                 std::to_string(rb) + " (" + eb + ")");
        }
        reads_ += n;
        check_time();
    }

    void advance()
    {
        uint64_t d;
        switch (rng_() % 10) {
        case 0: d = rng_() % (long_ns_ + 1); break; // up to 2 ms (--long)
        case 1: case 2: d = rng_() % 100000; break; // up to 100 us
        default: d = rng_() % 1000; break;
        }
        uint64_t t = rtl_.m->now_ns() + d;
        rtl_.m->run_until(t);
        fast_.m->run_until(t);
        check_time();
    }

    void random_drive()
    {
        uint32_t pin = rng_() % info_.io_width;
        uint32_t mode = rng_() % 3;
        std::string err;
        uint64_t now = rtl_.m->now_ns();
        if (rtl_.pins->drive(pin, mode, now, err) < 0 || fast_.pins->drive(pin, mode, now, err) < 0)
            die(err);
    }

    void random_quad()
    {
        std::vector<uint32_t> enc;
        for (uint32_t p = 0; p < cfg_.io_width; p++)
            if (cfg_.pins[p].sec_tag == vb::fast::kTagEncoder && !(cfg_.pins[p].sec_pin & 0x80))
                enc.push_back(p);
        if (enc.size() < 2)
            return advance();
        vb_quad q{};
        q.pin_a = enc[rng_() % enc.size()];
        q.pin_b = enc[rng_() % enc.size()];
        if (q.pin_a == q.pin_b)
            return;
        q.pin_index = UINT32_MAX;
        q.counts_per_s = (rng_() % 3 == 0) ? 0.0 : (static_cast<double>(rng_() % 4000000) - 2e6);
        std::string err;
        uint64_t now = rtl_.m->now_ns();
        int a = rtl_.pins->quad(q, now, err);
        int b = fast_.pins->quad(q, now, err);
        if (a != b)
            fail("quad source set-up differs between the banks: " + err);
    }

    void check_time()
    {
        if (rtl_.m->now_ns() != fast_.m->now_ns())
            fail("board time: RTL " + std::to_string(rtl_.m->now_ns()) + " ns, fast " +
                 std::to_string(fast_.m->now_ns()) + " ns");
    }

    void compare_logs()
    {
        const auto &a = rtl_.agent->log;
        const auto &b = fast_.agent->log;
        size_t n = std::min(a.size(), b.size());
        for (size_t i = checked_; i < n; i++)
            if (!(a[i] == b[i]))
                fail("pin edge " + std::to_string(i) + ": RTL pin " + std::to_string(a[i].pin) +
                         " -> " + std::to_string(a[i].level) + " at " + std::to_string(a[i].t) +
                         " ns, fast pin " + std::to_string(b[i].pin) + " -> " +
                         std::to_string(b[i].level) + " at " + std::to_string(b[i].t) + " ns",
                     std::min(a[i].t, b[i].t));
        if (a.size() != b.size()) {
            const Change &c = a.size() > b.size() ? a[n] : b[n];
            fail(std::string(a.size() > b.size() ? "RTL" : "fast") + " has an extra pin edge: pin " +
                     std::to_string(c.pin) + " -> " + std::to_string(c.level) + " at " +
                     std::to_string(c.t) + " ns",
                 c.t);
        }
        checked_ = n;
    }

    [[noreturn]] void fail(const std::string &what, uint64_t t = UINT64_MAX)
    {
        if (t == UINT64_MAX)
            t = rtl_.m->now_ns();
        std::fprintf(stderr,
                     "vboard-fastdiff: DIVERGENCE %s %s module %s at operation %" PRIu64
                     ", board time %" PRIu64 " ns, ClockLow cycle %" PRIu64 ": %s\n",
                     info_.board, info_.firmware, module_.c_str(), op_, t, t / tl_, what.c_str());
        std::exit(1);
    }

    static std::string hex(uint32_t v, int w)
    {
        char b[16];
        std::snprintf(b, sizeof b, "%0*x", w, v);
        return b;
    }

    const vb::FwInfo &info_;
    vb::fast::Config cfg_;
    std::mt19937_64 rng_;
    std::string module_;
    uint64_t tl_ = 30;
    Side rtl_, fast_;
    std::vector<Range> ranges_;
    Range io_{0, 0, 0};
    uint16_t sg_base_ = 0, pwm_base_ = 0;
    uint64_t op_ = 0, reads_ = 0;

  public:
    uint64_t long_ns_ = 2000000; // the longest advance (one operation in 10)

  private:
    size_t checked_ = 0;
};

} // namespace

int main(int argc, char **argv)
{
    std::string board, fw, module = "all";
    uint64_t ops = 10000;
    uint32_t seed = 1;
    uint64_t long_ns = 2000000;
    for (int i = 1; i + 1 < argc; i += 2) {
        std::string k = argv[i], v = argv[i + 1];
        if (k == "--board")
            board = v;
        else if (k == "--firmware")
            fw = v;
        else if (k == "--module")
            module = v;
        else if (k == "--ops")
            ops = std::strtoull(v.c_str(), nullptr, 10);
        else if (k == "--long")
            long_ns = std::strtoull(v.c_str(), nullptr, 10);
        else if (k == "--seed")
            seed = static_cast<uint32_t>(std::strtoul(v.c_str(), nullptr, 10));
        else
            die("unknown option " + k);
    }
    if (argc % 2 == 0 || board.empty() || fw.empty())
        die("usage: vboard-fastdiff --board B --firmware F [--module M] [--ops N] [--seed S]");
    const vb::LbEntry *e = nullptr;
    for (size_t i = 0; i < vb::kNumLbModels; i++)
        if (board == vb::kLbModels[i].info->board && fw == vb::kLbModels[i].info->firmware)
            e = &vb::kLbModels[i];
    const uint32_t *idrom = vb::fast::find_idrom(board.c_str(), fw.c_str());
    if (!e || !idrom)
        die("no local-bus firmware " + board + "/" + fw + " in this build");
    Diff d(*e, idrom, module, seed);
    d.long_ns_ = long_ns;
    d.run(ops);
    return 0;
}
