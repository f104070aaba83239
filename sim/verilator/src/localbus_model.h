// SPDX-License-Identifier: GPL-2.0-or-later
//
// localbus_model.h - LbModel<V>: one Verilated hm2 local-bus firmware
// (top from tools/hm2gen, wrapper hm2_top_localbus) running against the
// pin layer.  Included only by the generated lb_models.cpp, which
// instantiates it once per Verilated firmware.
//
// Clocks.  Board time is in ns.  ClockHigh has an integral period Th (10 ns
// at 100 MHz, 5 ns at 200 MHz); ClockLow is exactly R = ClockHigh/ClockLow
// (rounded: 3 for 100 / 33.33 MHz) ClockHigh periods, its rising edge on
// every R-th ClockHigh rising edge, so the ratio is exact and there is one
// time base.  The firmware only uses rising edges; ClockLow's falling edge
// is put on the ClockHigh falling edge of cycle (R-1)/2 for the waveform.
// Edge k of ClockHigh is at k*Th after the model started.
//
// Evaluation.  V::eval() wraps the model's scheduler in per-call cleanup
// that takes two mutexes (garbage of dynamic objects, the message queue of
// $display); at six evaluations per ClockLow cycle that was ~16% of the
// board's time (perf, 5i20 SVST8_4).  Between the edges of one request the
// model calls the scheduler itself (RootEval, the Verilated root's _eval
// named by the generated lb_models.cpp) and runs the full V::eval() once at
// the end of each request and every kFlushEdges edges, which delivers any
// queued message; a running waveform dump uses V::eval() throughout, and
// so does every evaluation with VBOARD_EVAL=full in the environment (for
// bench/vboard's before/after figure).
//
// Falling edges.  The firmware reacts to rising edges only (the build
// checks its sources for `negedge`: VB_FIRMWARE_USES_NEGEDGE), so the
// evaluation after a clock falls would only record the new clock levels in
// the scheduler's edge detectors and settle combinational logic that the
// next evaluation settles again before any flip-flop sees it.  The model
// writes those levels itself instead (the detectors are the root's
// __Vtrigprevexpr___TOP__clk_{high,low}__0, found at compile time; a
// firmware without them, or a running dump, still evaluates): +9 % on the
// 5i20 SVST8_4.
#ifndef VBOARD_LOCALBUS_MODEL_H
#define VBOARD_LOCALBUS_MODEL_H

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <type_traits>

#include <unistd.h>

#include "localbus.h"
#include "vcd2fst.h"
#include "verilated.h"
#include "verilated_vcd_c.h"

namespace vb {

namespace port {
// Copy pin vectors (32-bit words, pin 0 = bit 0) to and from Verilator's
// port types, whatever width the firmware has.
inline void put(CData &d, const uint32_t *w) { d = static_cast<CData>(w[0]); }
inline void put(SData &d, const uint32_t *w) { d = static_cast<SData>(w[0]); }
inline void put(IData &d, const uint32_t *w) { d = w[0]; }
inline void put(QData &d, const uint32_t *w) { d = w[0] | static_cast<QData>(w[1]) << 32; }
template <std::size_t N> inline void put(VlWide<N> &d, const uint32_t *w)
{
    for (std::size_t i = 0; i < N; i++)
        d[i] = w[i];
}
inline void get(CData d, uint32_t *w) { w[0] = d; }
inline void get(SData d, uint32_t *w) { w[0] = d; }
inline void get(IData d, uint32_t *w) { w[0] = d; }
inline void get(QData d, uint32_t *w)
{
    w[0] = static_cast<uint32_t>(d);
    w[1] = static_cast<uint32_t>(d >> 32);
}
template <std::size_t N> inline void get(const VlWide<N> &d, uint32_t *w)
{
    for (std::size_t i = 0; i < N; i++)
        w[i] = d[i];
}
} // namespace port

// Whether the Verilated root R has edge detectors for both clocks.
template <class R, class = void> struct HasClockDetectors : std::false_type {};
template <class R>
struct HasClockDetectors<R, std::void_t<decltype(R::__Vtrigprevexpr___TOP__clk_high__0),
                                        decltype(R::__Vtrigprevexpr___TOP__clk_low__0)>>
    : std::true_type {};

template <class V, auto RootEval> class LbModel final : public LbModelBase {
  public:
    static constexpr int kResetCycles = 4; // ClockLow cycles of rst after configuration
    static constexpr uint64_t kFlushEdges = 1u << 16; // full V::eval() at least this often
    // ClockLow cycles the design runs after reset before the host can reach
    // it (an FPGA's start-up; the hm2 watchdog's power-up bite is over then)
    static constexpr int kStartupCycles = 4;

    LbModel(const FwInfo &info, PinBank &pins, uint64_t start)
        : pins_(pins), th_(1000000000ull / info.clock_high_hz),
          ratio_((info.clock_high_hz + info.clock_low_hz / 2) / info.clock_low_hz),
          out_(pins.words()), oe_(pins.words())
    {
        if (!info.uses_clock_high) {
            // No logic on ClockHigh: step ClockLow edges only (ClockHigh
            // toggles with ClockLow, which nothing can tell apart).  Exact,
            // and several times faster on boards with a fast ClockHigh.
            th_ *= ratio_;
            ratio_ = 1;
        }
        const char *ev = std::getenv("VBOARD_EVAL");
        full_eval_ = ev && std::strcmp(ev, "full") == 0;
        ctx_ = std::make_unique<VerilatedContext>();
        ctx_->traceEverOn(true);
        m_ = std::make_unique<V>(ctx_.get(), "top");
        // The model starts at the first ClockHigh edge at or after `start`.
        next_edge_ = (start + th_ - 1) / th_ * th_;
        now_ = start;
        m_->clk_low = 0;
        m_->clk_high = 0;
        m_->rst = 1;
        m_->lb_wr = 0;
        m_->lb_rd = 0;
        m_->lb_addr = 0;
        m_->lb_wdata = 0;
        port::put(m_->io_in, pins_.inputs());
        m_->eval();
        for (int i = 0; i < kResetCycles; i++)
            low_cycle();
        m_->rst = 0;
        for (int i = 0; i < kStartupCycles; i++)
            low_cycle();
    }

    ~LbModel() override
    {
        std::string err;
        if (close_dump(err) < 0)
            std::fprintf(stderr, "vboard: %s\n", err.c_str());
        m_->final();
    }

    uint64_t now_ns() const override { return now_; }

    void run_until(uint64_t t) override
    {
        while (next_edge_ <= t)
            edge();
        flush();
        if (t > now_)
            now_ = t;
    }

    int read(const vb_xfer *x, size_t n, std::vector<uint8_t> &out, std::string &err) override
    {
        // Read i is on the bus during ClockLow edge i; its data is valid
        // after edge i+1 (lb_rvalid, hm2_localbus.v).
        std::vector<uint32_t> addrs;
        for (size_t i = 0; i < n; i++)
            for (uint32_t off = 0; off < x[i].size; off += 4)
                addrs.push_back(x[i].addr + off);
        size_t base = out.size();
        out.resize(base + addrs.size() * 4);
        for (size_t e = 0; e <= addrs.size(); e++) {
            if (e < addrs.size()) {
                m_->lb_rd = 1;
                m_->lb_addr = static_cast<SData>(addrs[e]);
            } else {
                m_->lb_rd = 0;
            }
            low_cycle();
            if (e == 0)
                continue;
            if (!m_->lb_rvalid) {
                m_->lb_rd = 0;
                flush();
                out.resize(base);
                err = "local bus: read of 0x" + hex(addrs[e - 1]) +
                      " got no lb_rvalid from the firmware";
                return -EIO;
            }
            uint32_t v = m_->lb_rdata;
            std::memcpy(&out[base + (e - 1) * 4], &v, 4); // host is little-endian
        }
        flush();
        return 0;
    }

    void write(const vb_xfer *x, size_t n, const uint8_t *data) override
    {
        for (size_t i = 0; i < n; i++)
            for (uint32_t off = 0; off < x[i].size; off += 4) {
                uint32_t v;
                std::memcpy(&v, data, 4);
                data += 4;
                m_->lb_wr = 1;
                m_->lb_addr = static_cast<SData>(x[i].addr + off);
                m_->lb_wdata = v;
                low_cycle();
            }
        m_->lb_wr = 0;
        // Two more clocks: the strobe is registered once, then the module
        // register takes the value; after that a probe sees the effect.
        low_cycle();
        low_cycle();
        flush();
    }

    int dump(bool on, const std::string &path, std::string &err) override
    {
        if (!on)
            return close_dump(err);
        if (vcd_) {
            err = "dump: a waveform dump is already running; stop it first";
            return -EBUSY;
        }
        // FST: trace VCD next to it, converted when the dump is closed.
        bool fst = path.size() >= 4 && path.compare(path.size() - 4, 4, ".fst") == 0;
        std::string file = fst ? path + ".tmp.vcd" : path;
        auto f = std::make_unique<VerilatedVcdC>();
        m_->trace(f.get(), 99);
        f->open(file.c_str());
        if (!f->isOpen()) {
            err = "dump: cannot open " + file + " for writing";
            return -EIO;
        }
        vcd_ = std::move(f);
        fst_path_ = fst ? path : "";
        vcd_path_ = file;
        return 0;
    }

  private:
    int close_dump(std::string &err)
    {
        if (!vcd_)
            return 0;
        vcd_->close();
        vcd_.reset();
        int rc = 0;
        if (!fst_path_.empty()) {
            rc = vcd_to_fst(vcd_path_, fst_path_, err);
            ::unlink(vcd_path_.c_str());
        }
        fst_path_.clear();
        return rc;
    }

    static std::string hex(uint32_t v)
    {
        char b[12];
        std::snprintf(b, sizeof b, "%04x", v);
        return b;
    }

    // Evaluate after an input change: the scheduler alone, or the full
    // V::eval() while dumping and every kFlushEdges calls.
    void eval()
    {
        if (full_eval_ || vcd_ || ++since_flush_ >= kFlushEdges) {
            flush();
            return;
        }
        m_->rootp->vlSymsp->__Vm_activity = true; // as V::eval() does, for tracing
        RootEval(m_->rootp);
    }

    // The full V::eval(): with no input change since the last evaluation it
    // only delivers queued messages and releases garbage.
    void flush()
    {
        m_->eval();
        since_flush_ = 0;
    }

    // After a clock fell: record the levels in the edge detectors, or
    // evaluate (see "Falling edges" at the top).
    void clocks_fell()
    {
        using Root = std::remove_pointer_t<decltype(m_->rootp)>;
#ifndef VB_FIRMWARE_USES_NEGEDGE
        if constexpr (HasClockDetectors<Root>::value) {
            if (!vcd_ && !full_eval_) {
                m_->rootp->__Vtrigprevexpr___TOP__clk_high__0 = m_->clk_high;
                m_->rootp->__Vtrigprevexpr___TOP__clk_low__0 = m_->clk_low;
                return;
            }
        }
#endif
        eval();
    }

    // One ClockHigh cycle: rising edge at next_edge_, falling edge Th/2 later.
    void edge()
    {
        uint64_t t = next_edge_;
        if (pins_.next_event_ns() <= t)
            pins_.run_events(t);
        port::put(m_->io_in, pins_.inputs());
        unsigned phase = static_cast<unsigned>(k_ % ratio_);
        m_->clk_high = 1;
        if (phase == 0)
            m_->clk_low = 1;
        eval();
        if (vcd_)
            vcd_->dump(t * 1000);
        port::get(m_->io_out, out_.data());
        port::get(m_->io_oe, oe_.data());
        pins_.set_fpga(out_.data(), oe_.data(), t);
        m_->clk_high = 0;
        if (phase == (ratio_ - 1) / 2)
            m_->clk_low = 0;
        clocks_fell();
        if (vcd_)
            vcd_->dump(t * 1000 + th_ * 500);
        k_++;
        next_edge_ += th_;
        now_ = t;
    }

    // Run edges up to and including the next ClockLow rising edge.
    void low_cycle()
    {
        for (;;) {
            bool low = k_ % ratio_ == 0;
            edge();
            if (low)
                break;
        }
    }

    PinBank &pins_;
    uint64_t th_;
    uint64_t ratio_;
    std::vector<uint32_t> out_, oe_;
    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<V> m_;
    std::unique_ptr<VerilatedVcdC> vcd_;
    std::string vcd_path_, fst_path_; // fst_path_ set: convert vcd_path_ on close
    uint64_t next_edge_ = 0, now_ = 0, k_ = 0, since_flush_ = 0;
    bool full_eval_ = false;
};

template <class V, auto RootEval>
std::unique_ptr<LbModelBase> make_lb_model(const FwInfo &info, PinBank &pins, uint64_t start)
{
    return std::make_unique<LbModel<V, RootEval>>(info, pins, start);
}

} // namespace vb

#endif // VBOARD_LOCALBUS_MODEL_H
