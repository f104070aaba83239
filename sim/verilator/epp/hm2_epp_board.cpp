// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_epp_board.cpp - the virtual Mesa 7i43: the Verilated hm2 firmwares
// with the EPP front end (hm2_top_epp: SVST4_4, SV8) behind a PC parallel
// port, and the board's CPLD that configures the FPGA (spec/hostmot2.md
// section 17.2; docs/vboard.md "7i43").
//
// While the FPGA is blank the CPLD answers EPP cycles at once: an address
// write selects register D0 (0 config data, 1 control); a data write to the
// control register drives PROG_B from D0 (0 clears the FPGA and restarts
// the configuration), to the data register clocks one bitstream byte in
// (the driver sends the .BIT 'e' chunk bit-reversed, as SelectMAP wants it;
// the board reverses it back); a read of the control register gives DONE in
// D0, of the data register the FPGA size (1 = 400K).  After a whole image
// (fwimage.h) the board checks it and starts that firmware (DONE = 1); a
// bad image leaves it blank and says why on stderr.  Running, the firmware
// answers the EPP cycles pin-level; its `reconfig` pulse (data 0x5A at
// address 0x7F7F) hands the board back to the CPLD.
//
// Pins are the IDROM's I/O pins 0..47 (P4 = 0..23, P3 = 24..47).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "epp_port_board.h"
#include "fwimage.h"
#include "fwinfo.h"
#include "fwinfo_hm2_7i43_sv8.h"
#include "fwinfo_hm2_7i43_svst4_4.h"
#include "verilated.h"
#include "Vhm2_7i43_sv8.h"
#include "Vhm2_7i43_svst4_4.h"

namespace vb {
namespace {

constexpr uint32_t kIoWidth = 48;

struct EppIn {
    uint8_t d = 0xFF;
    bool nwrite = true, ndatastr = true, naddrstr = true;
    uint64_t io_in = ~0ull;
};
struct EppOut {
    uint8_t d = 0;
    bool d_oe = false, nwait = false, reconfig = false;
    uint64_t io_out = 0, io_oe = 0;
};

class Hm2EppModel {
  public:
    virtual ~Hm2EppModel() = default;
    // One ClockHigh period; ClockLow rises every `ratio` of them.
    virtual void clock(const EppIn &in, EppOut &out) = 0;
};

template <class V> class Hm2EppModelT final : public Hm2EppModel {
  public:
    explicit Hm2EppModelT(uint32_t ratio) : ratio_(ratio), ctx_(std::make_unique<VerilatedContext>())
    {
        m_ = std::make_unique<V>(ctx_.get(), "hm2");
        EppIn idle;
        EppOut o;
        m_->rst = 1;
        for (uint32_t i = 0; i < 4 * ratio_; i++)
            clock(idle, o);
        m_->rst = 0;
        // start-up: the design runs a few ClockLow cycles before the host
        // can reach it (the hm2 watchdog's power-up bite is over then)
        for (uint32_t i = 0; i < 4 * ratio_; i++)
            clock(idle, o);
    }
    void clock(const EppIn &in, EppOut &out) override
    {
        m_->epp_d_i = in.d;
        m_->epp_nwrite = in.nwrite;
        m_->epp_ndatastr = in.ndatastr;
        m_->epp_naddrstr = in.naddrstr;
        m_->io_in = in.io_in;
        uint32_t phase = static_cast<uint32_t>(k_ % ratio_);
        m_->clk_high = 1;
        if (phase == 0)
            m_->clk_low = 1;
        m_->eval();
        m_->clk_high = 0;
        if (phase == (ratio_ - 1) / 2)
            m_->clk_low = 0;
        m_->eval();
        k_++;
        out.d = m_->epp_d_o;
        out.d_oe = m_->epp_d_oe;
        out.nwait = m_->epp_nwait;
        out.reconfig = m_->reconfig;
        out.io_out = m_->io_out;
        out.io_oe = m_->io_oe;
    }

  private:
    uint32_t ratio_;
    uint64_t k_ = 0;
    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<V> m_;
};

struct Hm2EppFw {
    const FwInfo *info;
    std::unique_ptr<Hm2EppModel> (*make)(uint32_t ratio);
};

template <class V> std::unique_ptr<Hm2EppModel> make_model(uint32_t ratio)
{
    return std::make_unique<Hm2EppModelT<V>>(ratio);
}

const Hm2EppFw kFws[] = {
    {&kFwInfo_hm2_7i43_svst4_4, &make_model<Vhm2_7i43_svst4_4>},
    {&kFwInfo_hm2_7i43_sv8, &make_model<Vhm2_7i43_sv8>},
};

uint8_t reverse8(uint8_t b)
{
    b = static_cast<uint8_t>((b & 0xF0) >> 4 | (b & 0x0F) << 4);
    b = static_cast<uint8_t>((b & 0xCC) >> 2 | (b & 0x33) << 2);
    return static_cast<uint8_t>((b & 0xAA) >> 1 | (b & 0x55) << 1);
}

class Hm2EppBoard final : public EppPortBoard {
  public:
    Hm2EppBoard() : pins_(kIoWidth) {}

    std::string name() const override { return "7i43"; }
    std::string fpga_part() const override { return kFws[0].info->fpga_part; }
    uint32_t bus() const override { return VB_BUS_EPP_HM2; }
    std::string firmware() const override { return fw_ ? fw_->info->firmware : ""; }
    uint32_t clock_low_hz() const override { return fw_ ? fw_->info->clock_low_hz : 0; }
    uint32_t clock_high_hz() const override { return fw_ ? fw_->info->clock_high_hz : 0; }
    std::vector<std::string> firmwares() const override
    {
        std::vector<std::string> v;
        for (const Hm2EppFw &f : kFws)
            v.push_back(f.info->firmware);
        return v;
    }
    std::vector<std::pair<std::string, std::string>>
    pin_names(const std::string &firmware) const override
    {
        std::vector<std::pair<std::string, std::string>> v;
        for (const Hm2EppFw &f : kFws)
            if (firmware == f.info->firmware)
                for (uint32_t p = 0; p < f.info->io_width; p++)
                    v.emplace_back(f.info->pins[p].label, f.info->pins[p].function);
        return v;
    }
    PinBank &pins() override { return pins_; }

    void run_until(uint64_t t) override
    {
        if (!model_) {
            if (t > now_) {
                pins_.run_events(t);
                now_ = t;
            }
            return;
        }
        while (model_ && now_ + th_ <= t)
            step();
        if (!model_ && t > now_)
            run_until(t);
    }

    int config(uint32_t op, const uint8_t *, size_t, vb_config_status &st,
               std::string &err) override
    {
        std::memset(&st, 0, sizeof st);
        st.done = fw_ ? 1 : 0;
        st.init = 1;
        std::strncpy(st.firmware, firmware().c_str(), sizeof st.firmware - 1);
        if (op == VB_CONFIG_STATUS)
            return 0;
        err = "7i43: the 7i43 is configured through its CPLD over EPP, not through the "
              "configuration port";
        return -ENOTSUP;
    }

    int load(const std::string &firmware, std::string &err) override
    {
        const Hm2EppFw *f = find(firmware);
        if (!f) {
            err = "firmware " + firmware + " is not built into this vboard for board 7i43";
            return -ENOENT;
        }
        start(*f);
        return 0;
    }

  protected:
    bool fpga_running() const override { return model_ != nullptr; }
    uint64_t step_ns() const override { return th_; }
    bool fpga_nwait() const override { return out_.nwait; }
    bool fpga_data(uint8_t &d) const override
    {
        d = out_.d;
        return out_.d_oe;
    }

    void step() override
    {
        uint64_t t = now_ + th_;
        if (pins_.next_event_ns() <= t)
            pins_.run_events(t);
        const uint32_t *lv = pins_.inputs();
        EppIn in;
        in.d = bus_.d;
        in.nwrite = bus_.nwrite;
        in.ndatastr = bus_.ndatastr;
        in.naddrstr = bus_.naddrstr;
        in.io_in = lv[0] | (static_cast<uint64_t>(lv[1]) << 32);
        model_->clock(in, out_);
        uint32_t ow[2] = {static_cast<uint32_t>(out_.io_out), static_cast<uint32_t>(out_.io_out >> 32)};
        uint32_t ew[2] = {static_cast<uint32_t>(out_.io_oe), static_cast<uint32_t>(out_.io_oe >> 32)};
        pins_.set_fpga(ow, ew, t);
        now_ = t;
        if (out_.reconfig) {
            std::fprintf(stderr, "vboard: 7i43: RECONFIG from firmware %s: FPGA cleared\n",
                         fw_->info->firmware);
            unconfigure();
        }
    }

    // The CPLD (FPGA blank).
    bool blank_cycle(bool addr, bool write, uint8_t w, uint8_t &r) override
    {
        if (addr) {
            if (write)
                reg_ = w & 1u;
            else
                r = reg_;
            return true;
        }
        if (reg_ == 1) {
            if (!write) {
                r = fw_ ? 1 : 0; // DONE
                return true;
            }
            bool prog = (w & 1u) != 0;
            if (!prog) {
                cfg_.clear();
                cfg_done_ = false;
            }
            prog_b_ = prog;
            return true;
        }
        if (!write) {
            r = 1; // 400K part
            return true;
        }
        if (prog_b_ && !cfg_done_) {
            cfg_.push_back(reverse8(w));
            if (cfg_.size() == kFwImageSize)
                finish_config();
        }
        return true;
    }

  private:
    static const Hm2EppFw *find(const std::string &name)
    {
        for (const Hm2EppFw &f : kFws)
            if (name == f.info->firmware)
                return &f;
        return nullptr;
    }

    void start(const Hm2EppFw &f)
    {
        fw_ = &f;
        uint32_t ratio = f.info->clock_high_hz / f.info->clock_low_hz;
        th_ = 1000000000ull / f.info->clock_high_hz;
        model_ = f.make(ratio ? ratio : 1);
        out_ = EppOut{};
    }

    void unconfigure()
    {
        model_.reset();
        fw_ = nullptr;
        cfg_.clear();
        cfg_done_ = false;
        pins_.release_fpga(now_);
    }

    void finish_config()
    {
        cfg_done_ = true;
        std::string err;
        std::vector<BuiltFw> built;
        for (const Hm2EppFw &f : kFws)
            built.push_back({f.info->firmware, f.info->idrom_crc});
        int i = match_fw_image(cfg_.data(), cfg_.size(), "7i43", built, "IDROM CRC", err);
        if (i >= 0) {
            std::fprintf(stderr, "vboard: 7i43: configured with %s\n", kFws[i].info->firmware);
            start(kFws[i]);
            return;
        }
        std::fprintf(stderr, "vboard: 7i43: configuration failed, board stays blank: %s\n",
                     err.c_str());
    }

    PinBank pins_;
    const Hm2EppFw *fw_ = nullptr;
    std::unique_ptr<Hm2EppModel> model_;
    EppOut out_;
    uint64_t th_ = 10;
    uint8_t reg_ = 0;
    bool prog_b_ = true, cfg_done_ = false;
    std::vector<uint8_t> cfg_;
};

std::vector<std::string> hm2_epp_boards()
{
    return {"7i43"};
}

std::unique_ptr<Board> make_hm2_epp_board(const std::string &board)
{
    if (board != "7i43")
        return nullptr;
    return std::make_unique<Hm2EppBoard>();
}

} // namespace
} // namespace vb

extern const vb::BoardFactory vb_factory_hm2_epp;
const vb::BoardFactory vb_factory_hm2_epp = {vb::hm2_epp_boards, vb::make_hm2_epp_board};
