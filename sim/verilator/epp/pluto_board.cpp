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
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "epp_fpga_board.h"
#include "fwimage.h"
#include "Vpluto_servo.h"
#include "Vpluto_servo__Syms.h"
#include "Vpluto_step.h"
#include "Vpluto_step__Syms.h"

// The Verilated roots' schedulers (defined in the models).
void Vpluto_servo___024root___eval(Vpluto_servo___024root *vlSelf);
void Vpluto_step___024root___eval(Vpluto_step___024root *vlSelf);

namespace vb {
namespace {

constexpr uint64_t kClockNs = 25; // 40 MHz
constexpr uint32_t kPins = 43;
constexpr uint32_t kFirstInput = 23;

// Whether the Verilated root R has an edge detector for clk.
template <class R, class = void> struct HasClkDetector : std::false_type {};
template <class R>
struct HasClkDetector<R, std::void_t<decltype(R::__Vtrigprevexpr___TOP__clk__0)>>
    : std::true_type {};

// One 40 MHz clock per clock(); nInit is the EPP front end's nReset.
//
// Evaluation, as in localbus_model.h: a clock calls the Verilated
// scheduler (the root's _eval, RootEval) instead of V::eval(), whose
// per-call cleanup takes two mutexes, with a full V::eval() every
// kFlushClocks clocks (queued messages), and does not evaluate after the
// clock falls: the firmware reacts to rising edges only (no `negedge` in
// hdl/pluto; its asynchronous resets rise with a clock or with rst, both
// seen by the rising evaluation), so the model writes the low level into
// the clock's edge detector itself.  VBOARD_EVAL=full in the environment
// evaluates fully at both edges (bench figures).
template <class V, auto RootEval> class PlutoModelT final : public EppFpgaModelT<V> {
  public:
    static constexpr uint32_t kFlushClocks = 1u << 16;

    PlutoModelT() : EppFpgaModelT<V>("pluto")
    {
        const char *ev = std::getenv("VBOARD_EVAL");
        full_eval_ = ev && std::strcmp(ev, "full") == 0;
        V &m = *this->m_;
        m.clk = 0;
        m.rst = 1;
        m.eval(); // initial blocks and settling: the full evaluation once
        this->reset(4);
    }
    void clock(const EppFpgaIn &in, EppFpgaOut &out) override
    {
        using Root = std::remove_pointer_t<decltype(this->m_->rootp)>;
        constexpr bool fast = HasClkDetector<Root>::value;
        V &m = *this->m_;
        this->drive_epp(in);
        m.epp_nreset = in.nreset;
        m.io_in = static_cast<uint32_t>(in.io_in);
        m.clk = 1;
        if (!fast || full_eval_ || ++since_flush_ >= kFlushClocks) {
            m.eval();
            since_flush_ = 0;
        } else {
            m.rootp->vlSymsp->__Vm_activity = true; // as V::eval() does
            RootEval(m.rootp);
        }
        m.clk = 0;
        if constexpr (fast) {
            if (full_eval_)
                m.eval();
            else
                m.rootp->__Vtrigprevexpr___TOP__clk__0 = 0;
        } else {
            m.eval();
        }
        this->sample(out);
    }

  private:
    uint32_t since_flush_ = 0;
    bool full_eval_ = false;
};

struct PlutoFw {
    const char *name;
    uint32_t n_out, n_in;
    std::unique_ptr<EppFpgaModel> (*make)();
};

template <class V, auto RootEval> std::unique_ptr<EppFpgaModel> make_model()
{
    return std::make_unique<PlutoModelT<V, RootEval>>();
}

const PlutoFw kPlutoFws[] = {
    {"pluto_servo", 19, 20, &make_model<Vpluto_servo, &Vpluto_servo___024root___eval>},
    {"pluto_step", 23, 16, &make_model<Vpluto_step, &Vpluto_step___024root___eval>},
};
constexpr int kNumFws = static_cast<int>(sizeof kPlutoFws / sizeof kPlutoFws[0]);

// The image's "IDROM CRC" field for a Pluto firmware: CRC-32 of its name
// (the build's tools/vbfw call writes the same; there is no IDROM).
uint32_t design_id(const char *name)
{
    return crc32(reinterpret_cast<const uint8_t *>(name), std::strlen(name));
}

class PlutoBoard final : public EppFpgaBoard {
  public:
    PlutoBoard()
        : EppFpgaBoard("pluto", kPins,
                       "the Pluto-P is configured through its parallel port (nCONFIG/DCLK/DATA0 "
                       "on nInit/nStrobe/data)",
                       "design id")
    {
    }

    std::string fpga_part() const override { return "ep1k10tc100"; }
    uint32_t bus() const override { return VB_BUS_EPP_PLUTO; }
    uint32_t clock_low_hz() const override { return fw_ < 0 ? 0 : 40000000u; }
    uint32_t clock_high_hz() const override { return 0; }
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

  protected:
    int fw_count() const override { return kNumFws; }
    const char *fw_name(int i) const override { return kPlutoFws[i].name; }
    uint32_t fw_build_id(int i) const override { return design_id(kPlutoFws[i].name); }
    std::unique_ptr<EppFpgaModel> make_model(int i, uint64_t &step_ns) const override
    {
        step_ns = kClockNs;
        return kPlutoFws[i].make();
    }
    uint64_t fpga_inputs(uint64_t pins) const override
    {
        return (pins >> kFirstInput) & ((1ull << kPlutoFws[fw_].n_in) - 1);
    }
    uint64_t fpga_output_mask() const override { return (1ull << kPlutoFws[fw_].n_out) - 1; }

    // nInit (bit 2) is nCONFIG, nStrobe (bit 0, inverted by the port) DCLK.
    void control_written(uint8_t old, uint8_t v) override
    {
        bool ninit_was = (old & 0x04) != 0, ninit = (v & 0x04) != 0;
        bool dclk_was = (old & 0x01) == 0, dclk = (v & 0x01) == 0;
        if (ninit_was && !ninit) {
            // nCONFIG low: the FPGA clears itself and waits for a bitstream.
            if (fw_ >= 0)
                std::fprintf(stderr, "vboard: pluto: nCONFIG low: firmware %s cleared\n",
                             fw_name(fw_));
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
    void shift_in(unsigned bit)
    {
        if (nbits_ % 8 == 0)
            bits_.push_back(0);
        bits_.back() |= static_cast<uint8_t>(bit << (nbits_ % 8));
        nbits_++;
        if (nbits_ == kFwImageSize * 8) {
            loading_ = false;
            configure_from(bits_);
        }
    }

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
