// SPDX-License-Identifier: GPL-2.0-or-later
//
// pluto_board.cpp - the virtual Pluto-P: the Verilated pluto_servo or
// pluto_step firmware behind a PC parallel port (spec/pluto.md sections 1,
// 2 and 8; docs/vboard.md "Pluto-P").
//
// The board models what the host's port registers do to the board's pins:
//  * EPP address/data cycles run pin-level against the firmware's EPP front
//    end (nWrite, nDataStr, nAddrStr, data, nWait) one 40 MHz clock at a
//    time, with the PC port's 10 us timeout: no acknowledge (blank FPGA,
//    a stalled board) sets status bit 0 and aborts the cycle; while the bit
//    is set further cycles are skipped (reads give 0xFF) until the host
//    clears it, as a PC port does.
//  * The control register's nInit line (bit 2) is nCONFIG and the EPP
//    nReset; its nStrobe line (bit 0, inverted by the port) is DCLK; the SPP
//    data register's bit 0 is DATA0: the Altera passive-serial upload.  An
//    nCONFIG low pulse unconfigures the FPGA (all pins float, the LED is
//    faint); every DCLK rising edge shifts in one bit, LSB first; once a
//    whole image (fwimage.h) is in, it is checked and the firmware starts.
//    A wrong or short image leaves the board unconfigured and says why on
//    stderr; the driver's post-upload probe then times out.
//
// Pin numbering (fixed for both firmwares, so a probe client needs no
// table): pins 0..22 are the firmware's io_out/io_oe bits (pluto_servo uses
// 0..18: OUT0..9, UP/DN0..3, LED; pluto_step 0..22: OUT0..13, STEP/DIR0..3,
// LED), pins 23..42 are its io_in bits (pluto_servo IN0..7, QZ0..3, QB0..3,
// QA0..3 = pins 23..42; pluto_step IN0..15 = pins 23..38).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "epp_port_board.h"
#include "fwimage.h"
#include "pins.h"
#include "verilated.h"
#include "Vpluto_servo.h"
#include "Vpluto_step.h"

namespace vb {
namespace {

constexpr uint64_t kClockNs = 25; // 40 MHz
constexpr uint32_t kPins = 43;
constexpr uint32_t kFirstInput = 23;

// The firmware-facing signals of one clock.
struct PlutoIn {
    uint8_t d = 0xFF;
    bool nwrite = true, ndatastr = true, naddrstr = true, nreset = true;
    uint32_t io_in = 0;
};
struct PlutoOut {
    uint8_t d = 0;
    bool d_oe = false, nwait = false;
    uint32_t io_out = 0, io_oe = 0;
};

class PlutoModel {
  public:
    virtual ~PlutoModel() = default;
    virtual void clock(const PlutoIn &in, PlutoOut &out) = 0;
};

template <class V> class PlutoModelT final : public PlutoModel {
  public:
    PlutoModelT() : ctx_(std::make_unique<VerilatedContext>())
    {
        m_ = std::make_unique<V>(ctx_.get(), "pluto");
        PlutoIn idle;
        idle.io_in = 0xFFFFFFFFu;
        PlutoOut o;
        m_->rst = 1;
        for (int i = 0; i < 4; i++)
            clock(idle, o);
        m_->rst = 0;
    }
    void clock(const PlutoIn &in, PlutoOut &out) override
    {
        m_->epp_d_i = in.d;
        m_->epp_nwrite = in.nwrite;
        m_->epp_ndatastr = in.ndatastr;
        m_->epp_naddrstr = in.naddrstr;
        m_->epp_nreset = in.nreset;
        m_->io_in = in.io_in;
        m_->clk = 1;
        m_->eval();
        m_->clk = 0;
        m_->eval();
        out.d = m_->epp_d_o;
        out.d_oe = m_->epp_d_oe;
        out.nwait = m_->epp_nwait;
        out.io_out = m_->io_out;
        out.io_oe = m_->io_oe;
    }

  private:
    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<V> m_;
};

struct PlutoFw {
    const char *name;
    uint32_t n_out, n_in;
    std::unique_ptr<PlutoModel> (*make)();
};

template <class V> std::unique_ptr<PlutoModel> make_model()
{
    return std::make_unique<PlutoModelT<V>>();
}

const PlutoFw kPlutoFws[] = {
    {"pluto_servo", 19, 20, &make_model<Vpluto_servo>},
    {"pluto_step", 23, 16, &make_model<Vpluto_step>},
};

// The image's "IDROM CRC" field for a Pluto firmware: CRC-32 of its name
// (the build's tools/vbfw call writes the same; there is no IDROM).
uint32_t design_id(const char *name)
{
    return crc32(reinterpret_cast<const uint8_t *>(name), std::strlen(name));
}

class PlutoBoard final : public EppPortBoard {
  public:
    PlutoBoard() : pins_(kPins) {}

    std::string name() const override { return "pluto"; }
    std::string fpga_part() const override { return "ep1k10tc100"; }
    uint32_t bus() const override { return VB_BUS_EPP_PLUTO; }
    std::string firmware() const override { return fw_ ? fw_->name : ""; }
    uint32_t clock_low_hz() const override { return fw_ ? 40000000u : 0; }
    uint32_t clock_high_hz() const override { return 0; }
    std::vector<std::string> firmwares() const override
    {
        std::vector<std::string> v;
        for (const PlutoFw &f : kPlutoFws)
            v.push_back(f.name);
        return v;
    }
    std::vector<std::pair<std::string, std::string>>
    pin_names(const std::string &firmware) const override
    {
        // Pin names of the firmware docs (docs/pluto-*-firmware.md): pins
        // 0..22 outputs, 23..42 inputs.
        std::vector<std::string> n;
        if (firmware == "pluto_servo") {
            for (int i = 0; i < 10; i++)
                n.push_back("OUT" + std::to_string(i));
            for (int i = 0; i < 4; i++) {
                n.push_back("UP" + std::to_string(i));
                n.push_back("DN" + std::to_string(i));
            }
            n.push_back("LED");
            n.resize(kFirstInput);
            for (int i = 0; i < 8; i++)
                n.push_back("IN" + std::to_string(i));
            for (const char *q : {"QZ", "QB", "QA"})
                for (int i = 0; i < 4; i++)
                    n.push_back(q + std::to_string(i));
        } else if (firmware == "pluto_step") {
            for (int i = 0; i < 14; i++)
                n.push_back("OUT" + std::to_string(i));
            for (int i = 0; i < 4; i++) {
                n.push_back("STEP" + std::to_string(i));
                n.push_back("DIR" + std::to_string(i));
            }
            n.push_back("LED");
            for (int i = 0; i < 16; i++)
                n.push_back("IN" + std::to_string(i));
        } else {
            return {};
        }
        n.resize(kPins);
        std::vector<std::pair<std::string, std::string>> v;
        for (const std::string &name : n)
            v.emplace_back("", name);
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
        while (now_ + kClockNs <= t)
            step();
    }

    int config(uint32_t op, const uint8_t *, size_t, vb_config_status &st,
               std::string &err) override
    {
        std::memset(&st, 0, sizeof st);
        status(st);
        if (op == VB_CONFIG_STATUS)
            return 0;
        err = "pluto: the Pluto-P is configured through its parallel port (nCONFIG/DCLK/DATA0 "
              "on nInit/nStrobe/data), not through the configuration port";
        return -ENOTSUP;
    }

    int load(const std::string &firmware, std::string &err) override
    {
        const PlutoFw *f = find(firmware);
        if (!f) {
            err = "firmware " + firmware + " is not a Pluto-P firmware of this vboard "
                  "(built: pluto_servo, pluto_step)";
            return -ENOENT;
        }
        start(*f);
        return 0;
    }

  protected:
    bool fpga_running() const override { return model_ != nullptr; }
    uint64_t step_ns() const override { return kClockNs; }
    bool fpga_nwait() const override { return out_.nwait; }
    bool fpga_data(uint8_t &d) const override
    {
        d = out_.d;
        return out_.d_oe;
    }

    // One 40 MHz clock: inputs from the pins, outputs back to them.
    void step() override
    {
        uint64_t t = now_ + kClockNs;
        if (pins_.next_event_ns() <= t)
            pins_.run_events(t);
        const uint32_t *lv = pins_.inputs();
        uint64_t all = lv[0] | (static_cast<uint64_t>(lv[1]) << 32);
        PlutoIn in;
        in.d = bus_.d;
        in.nwrite = bus_.nwrite;
        in.ndatastr = bus_.ndatastr;
        in.naddrstr = bus_.naddrstr;
        in.nreset = (control_ & 0x04) != 0;
        in.io_in = static_cast<uint32_t>((all >> kFirstInput) & ((1ull << fw_->n_in) - 1));
        model_->clock(in, out_);
        uint64_t o = out_.io_out & ((1ull << fw_->n_out) - 1);
        uint64_t e = out_.io_oe & ((1ull << fw_->n_out) - 1);
        uint32_t ow[2] = {static_cast<uint32_t>(o), static_cast<uint32_t>(o >> 32)};
        uint32_t ew[2] = {static_cast<uint32_t>(e), static_cast<uint32_t>(e >> 32)};
        pins_.set_fpga(ow, ew, t);
        now_ = t;
    }

    // nInit (bit 2) is nCONFIG, nStrobe (bit 0, inverted by the port) DCLK.
    void control_written(uint8_t old, uint8_t v) override
    {
        bool ninit_was = (old & 0x04) != 0, ninit = (v & 0x04) != 0;
        bool dclk_was = (old & 0x01) == 0, dclk = (v & 0x01) == 0;
        if (ninit_was && !ninit) {
            // nCONFIG low: the FPGA clears itself and waits for a bitstream.
            if (fw_)
                std::fprintf(stderr, "vboard: pluto: nCONFIG low: firmware %s cleared\n",
                             fw_->name);
            unconfigure();
            loading_ = true;
            bits_.clear();
            nbits_ = 0;
            return;
        }
        if (loading_ && ninit && !dclk_was && dclk)
            shift_in(spp_ & 1u);
    }

  private:
    static const PlutoFw *find(const std::string &name)
    {
        for (const PlutoFw &f : kPlutoFws)
            if (name == f.name)
                return &f;
        return nullptr;
    }

    void status(vb_config_status &st) const
    {
        st.done = fw_ ? 1 : 0;
        st.init = 1;
        std::strncpy(st.firmware, firmware().c_str(), sizeof st.firmware - 1);
    }

    void start(const PlutoFw &f)
    {
        fw_ = &f;
        model_ = f.make();
        out_ = PlutoOut{};
    }

    void unconfigure()
    {
        model_.reset();
        fw_ = nullptr;
        pins_.release_fpga(now_);
    }

    void shift_in(unsigned bit)
    {
        if (nbits_ % 8 == 0)
            bits_.push_back(0);
        bits_.back() |= static_cast<uint8_t>(bit << (nbits_ % 8));
        nbits_++;
        if (nbits_ == kFwImageSize * 8)
            finish_upload();
    }

    void finish_upload()
    {
        loading_ = false;
        std::string err;
        std::vector<BuiltFw> built;
        for (const PlutoFw &f : kPlutoFws)
            built.push_back({f.name, design_id(f.name)});
        int i = match_fw_image(bits_.data(), bits_.size(), "pluto", built, "design id", err);
        if (i >= 0) {
            std::fprintf(stderr, "vboard: pluto: configured with %s\n", kPlutoFws[i].name);
            start(kPlutoFws[i]);
            return;
        }
        std::fprintf(stderr, "vboard: pluto: configuration failed, board stays blank: %s\n",
                     err.c_str());
    }
    PinBank pins_;
    const PlutoFw *fw_ = nullptr;
    std::unique_ptr<PlutoModel> model_;
    PlutoOut out_;
    bool loading_ = false;
    std::vector<uint8_t> bits_;
    size_t nbits_ = 0;
};

std::vector<std::string> pluto_boards()
{
    return {"pluto"};
}

std::unique_ptr<Board> make_pluto_board(const std::string &board)
{
    if (board != "pluto")
        return nullptr;
    return std::make_unique<PlutoBoard>();
}

} // namespace
} // namespace vb

extern const vb::BoardFactory vb_factory_pluto;
const vb::BoardFactory vb_factory_pluto = {vb::pluto_boards, vb::make_pluto_board};
