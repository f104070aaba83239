// SPDX-License-Identifier: GPL-2.0-or-later
//
// epp_fpga_board.h - an EPP board whose FPGA runs a Verilated firmware (the
// Pluto-P, the 7i43): what both boards do with it, beside the port itself
// (epp_port_board.h).  The firmware side of one fine clock: the EPP bus and
// the I/O pins in, the EPP data, nWait and the I/O pins out; the built-in
// firmwares by name (load, firmwares); starting one and clearing the FPGA
// again; a whole uploaded image checked against the firmwares built in
// (fwimage.h); the configuration-port status.  A subclass names its
// firmwares, makes their models and says how its pins map onto them.
#ifndef VBOARD_EPP_FPGA_BOARD_H
#define VBOARD_EPP_FPGA_BOARD_H

#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "epp_port_board.h"
#include "pins.h"
#include "verilated.h"

namespace vb {

// The firmware-facing signals of one fine clock.  I/O pins 0..63 in the
// 64-bit words, 64..95 (the 7i90's 72 pins) in the _hi ones.
struct EppFpgaIn {
    uint8_t d = 0xFF;
    bool nwrite = true, ndatastr = true, naddrstr = true, nreset = true;
    uint64_t io_in = ~0ull;
    uint32_t io_in_hi = ~0u;
};
struct EppFpgaOut {
    uint8_t d = 0;
    bool d_oe = false, nwait = false, reconfig = false;
    uint64_t io_out = 0, io_oe = 0;
    uint32_t io_out_hi = 0, io_oe_hi = 0;
};

// A Verilated I/O vector port (an integer up to 64 bits, a VlWide above)
// to and from the split words above.
template <class T> void epp_set_io(T &port, uint64_t lo, uint32_t hi)
{
    if constexpr (std::is_integral_v<T>) {
        (void)hi;
        port = static_cast<T>(lo);
    } else {
        port.at(0) = static_cast<uint32_t>(lo);
        port.at(1) = static_cast<uint32_t>(lo >> 32);
        port.at(2) = hi;
    }
}
template <class T> void epp_get_io(const T &port, uint64_t &lo, uint32_t &hi)
{
    if constexpr (std::is_integral_v<T>) {
        lo = port;
        hi = 0;
    } else {
        lo = port.at(0) | static_cast<uint64_t>(port.at(1)) << 32;
        hi = port.at(2);
    }
}

// A running firmware.
class EppFpgaModel {
  public:
    virtual ~EppFpgaModel() = default;
    // One fine clock (the firmware's fastest).
    virtual void clock(const EppFpgaIn &in, EppFpgaOut &out) = 0;
};

// A Verilated firmware V: its context and design, and the EPP front end's
// ports, named alike in every EPP firmware.  A subclass clocks it.
template <class V> class EppFpgaModelT : public EppFpgaModel {
  protected:
    explicit EppFpgaModelT(const char *name)
        : ctx_(std::make_unique<VerilatedContext>()), m_(std::make_unique<V>(ctx_.get(), name))
    {
    }
    // rst high for `cycles` fine clocks with the bus idle and the inputs
    // high, then low for `startup` more (a design the host may only reach
    // a while after reset).  Call from the subclass's constructor.
    void reset(uint32_t cycles, uint32_t startup = 0)
    {
        EppFpgaIn idle;
        EppFpgaOut o;
        m_->rst = 1;
        for (uint32_t i = 0; i < cycles; i++)
            clock(idle, o);
        m_->rst = 0;
        for (uint32_t i = 0; i < startup; i++)
            clock(idle, o);
    }
    void drive_epp(const EppFpgaIn &in)
    {
        m_->epp_d_i = in.d;
        m_->epp_nwrite = in.nwrite;
        m_->epp_ndatastr = in.ndatastr;
        m_->epp_naddrstr = in.naddrstr;
    }
    void sample(EppFpgaOut &out) const
    {
        out.d = m_->epp_d_o;
        out.d_oe = m_->epp_d_oe;
        out.nwait = m_->epp_nwait;
        epp_get_io(m_->io_out, out.io_out, out.io_out_hi);
        epp_get_io(m_->io_oe, out.io_oe, out.io_oe_hi);
    }

    std::unique_ptr<VerilatedContext> ctx_;
    std::unique_ptr<V> m_;
};

class EppFpgaBoard : public EppPortBoard {
  public:
    std::string name() const override { return board_; }
    std::string firmware() const override { return fw_ < 0 ? "" : fw_name(fw_); }
    std::vector<std::string> firmwares() const override;
    PinBank &pins() override { return pins_; }
    void run_until(uint64_t t) override;
    int config(uint32_t op, const uint8_t *, size_t, vb_config_status &st,
               std::string &err) override;
    int load(const std::string &firmware, std::string &err) override;

  protected:
    // board: "pluto"; how: the reply to a configuration-port write ("the
    // Pluto-P is configured through ..."); id_label: what an image's build
    // id is called in messages ("design id").
    EppFpgaBoard(const char *board, uint32_t npins, const char *how, const char *id_label)
        : board_(board), how_(how), id_label_(id_label), pins_(npins)
    {
    }

    // ---- the subclass's firmwares -----------------------------------------
    virtual int fw_count() const = 0;
    virtual const char *fw_name(int i) const = 0;
    virtual uint32_t fw_build_id(int i) const = 0;
    // A new model of firmware i, reset; *step_ns: its fine clock's period.
    virtual std::unique_ptr<EppFpgaModel> make_model(int i, uint64_t &step_ns) const = 0;
    // The firmware's io_in from the pin levels (pin p = bit p) and the
    // firmware's io_out/io_oe bits that reach pins; default: one to one.
    virtual uint64_t fpga_inputs(uint64_t pins) const { return pins; }
    virtual uint64_t fpga_output_mask() const { return ~0ull; }
    // After each fine clock (the 7i43's RECONFIG).
    virtual void stepped() {}

    bool fpga_running() const override { return model_ != nullptr; }
    uint64_t step_ns() const override { return th_; }
    bool fpga_nwait() const override { return out_.nwait; }
    bool fpga_data(uint8_t &d) const override
    {
        d = out_.d;
        return out_.d_oe;
    }
    // One fine clock: inputs from the pins, outputs back to them.
    void step() override;

    void start(int i);
    // Clear the FPGA: no firmware, every pin floats.
    void unconfigure();
    // A whole image came in: start the firmware it selects, or stay blank
    // and say why on stderr.
    void configure_from(const std::vector<uint8_t> &image);

    int fw_ = -1; // the running firmware, -1 while blank
    EppFpgaOut out_;

  private:
    const char *board_, *how_, *id_label_;
    PinBank pins_;
    std::unique_ptr<EppFpgaModel> model_;
    uint64_t th_ = 10;
};

} // namespace vb

#endif // VBOARD_EPP_FPGA_BOARD_H
