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

#include "board.h"
#include "fwimage.h"
#include "pins.h"
#include "verilated.h"
#include "Vpluto_servo.h"
#include "Vpluto_step.h"

namespace vb {
namespace {

constexpr uint64_t kClockNs = 25;          // 40 MHz
constexpr uint64_t kEppTimeoutNs = 10000;  // PC port: ~10 us
constexpr uint32_t kPins = 43;
constexpr uint32_t kFirstInput = 23;
constexpr uint8_t kStatusTimeout = 0x01;
// enum epp_op_kind (host/driver/include/hm2/epp_port.h)
enum : uint8_t {
    OP_ADDR_WRITE = 1, OP_ADDR_READ, OP_DATA_WRITE, OP_DATA_READ, OP_STATUS_READ,
    OP_STATUS_WRITE, OP_CONTROL_WRITE, OP_SPP_DATA_WRITE, OP_ECR_WRITE, OP_DELAY
};

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

class PlutoBoard final : public Board {
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
    PinBank &pins() override { return pins_; }
    uint64_t now_ns() const override { return now_; }

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
            clock();
    }

    int config(uint32_t op, const uint8_t *, size_t, vb_config_status &st,
               std::string &err) override
    {
        std::memset(&st, 0, sizeof st);
        if (op == VB_CONFIG_STATUS) {
            status(st);
            return 0;
        }
        status(st);
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

    int epp(const uint8_t *req, size_t len, std::vector<uint8_t> &out, std::string &err) override
    {
        // Parse everything first: a payload that does not parse changes nothing.
        size_t off = 0, nreads = 0;
        while (off < len) {
            vb_epp_op op;
            if (len - off < sizeof op) {
                err = "EPP request: truncated operation at byte " + std::to_string(off);
                return -EPROTO;
            }
            std::memcpy(&op, req + off, sizeof op);
            off += sizeof op;
            if (op.kind < OP_ADDR_WRITE || op.kind > OP_DELAY) {
                err = "EPP request: unknown operation kind " + std::to_string(op.kind) +
                      " at byte " + std::to_string(off - sizeof op);
                return -EPROTO;
            }
            if (op.kind == OP_DATA_WRITE) {
                if (len - off < op.n) {
                    err = "EPP request: data write of " + std::to_string(op.n) +
                          " bytes runs past the payload";
                    return -EPROTO;
                }
                off += op.n;
            }
            nreads += op.kind == OP_DATA_READ ? op.n
                      : (op.kind == OP_ADDR_READ || op.kind == OP_STATUS_READ) ? 1 : 0;
            if (nreads > VB_MAX_PAYLOAD) {
                err = "EPP request: reads more than the reply can carry";
                return -EPROTO;
            }
        }
        out.reserve(out.size() + nreads);
        for (off = 0; off < len;) {
            vb_epp_op op;
            std::memcpy(&op, req + off, sizeof op);
            off += sizeof op;
            execute(op, req + off, out);
            if (op.kind == OP_DATA_WRITE)
                off += op.n;
        }
        return 0;
    }

    int epp_stall(bool on, std::string &) override
    {
        stall_ = on;
        return 0;
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
        in_ = PlutoIn{};
        in_.nreset = nreset_pin();
    }

    void unconfigure()
    {
        model_.reset();
        fw_ = nullptr;
        pins_.release_fpga(now_);
    }

    bool nreset_pin() const { return (control_ & 0x04) != 0; }

    // One 40 MHz clock: inputs from the pins, outputs back to them.
    void clock()
    {
        uint64_t t = now_ + kClockNs;
        if (pins_.next_event_ns() <= t)
            pins_.run_events(t);
        const uint32_t *lv = pins_.inputs();
        uint64_t all = lv[0] | (static_cast<uint64_t>(lv[1]) << 32);
        in_.io_in = static_cast<uint32_t>((all >> kFirstInput) & ((1ull << fw_->n_in) - 1));
        model_->clock(in_, out_);
        uint64_t o = out_.io_out & ((1ull << fw_->n_out) - 1);
        uint64_t e = out_.io_oe & ((1ull << fw_->n_out) - 1);
        uint32_t ow[2] = {static_cast<uint32_t>(o), static_cast<uint32_t>(o >> 32)};
        uint32_t ew[2] = {static_cast<uint32_t>(e), static_cast<uint32_t>(e >> 32)};
        pins_.set_fpga(ow, ew, t);
        now_ = t;
    }

    void wait_ns(uint64_t ns)
    {
        if (model_) {
            uint64_t end = now_ + ns;
            while (now_ < end)
                clock();
        } else {
            run_until(now_ + ns);
        }
    }

    // The firmware acknowledges (nWait at the IEEE 1284 level 1) - never
    // while blank or stalled.
    bool ack() const { return model_ && !stall_ && out_.nwait; }

    // One EPP cycle, pin-level.  Returns false on a timeout.
    bool cycle(bool addr, bool write, uint8_t wbyte, uint8_t &rbyte)
    {
        rbyte = 0xFF;
        if (status_ & kStatusTimeout)
            return false; // the port refuses cycles until the bit is cleared
        in_.nwrite = !write;
        in_.d = write ? wbyte : 0xFF;
        wait_ns(kClockNs); // setup
        (addr ? in_.naddrstr : in_.ndatastr) = false;
        uint64_t start = now_;
        bool ok = true;
        while (!ack()) {
            if (now_ - start >= kEppTimeoutNs) {
                ok = false;
                break;
            }
            wait_ns(kClockNs);
        }
        if (ok && !write)
            rbyte = out_.d_oe ? out_.d : 0xFF;
        (addr ? in_.naddrstr : in_.ndatastr) = true;
        if (ok) {
            start = now_;
            while (ack() && now_ - start < kEppTimeoutNs)
                wait_ns(kClockNs);
            ok = !ack();
        }
        in_.nwrite = true;
        in_.d = 0xFF;
        wait_ns(kClockNs); // recovery
        if (!ok)
            status_ |= kStatusTimeout;
        return ok;
    }

    void control_write(uint8_t v)
    {
        bool ninit_was = (control_ & 0x04) != 0, ninit = (v & 0x04) != 0;
        bool dclk_was = (control_ & 0x01) == 0, dclk = (v & 0x01) == 0; // nStrobe inverted
        control_ = v;
        in_.nreset = ninit;
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
        FwImage img;
        std::string err;
        int rc = parse_fw_image(bits_.data(), bits_.size(), img, err);
        const PlutoFw *f = rc == 0 ? find(img.firmware) : nullptr;
        if (rc == 0 && img.board != "pluto")
            err = "image is for board " + img.board + ", this board is a Pluto-P";
        else if (rc == 0 && !f)
            err = "image names firmware " + img.firmware + ", not built into this vboard";
        else if (rc == 0 && img.idrom_crc != design_id(f->name))
            err = "image of " + img.firmware + " comes from another build (design id)";
        else if (rc == 0) {
            std::fprintf(stderr, "vboard: pluto: configured with %s\n", f->name);
            start(*f);
            return;
        }
        std::fprintf(stderr, "vboard: pluto: configuration failed, board stays unconfigured: %s\n",
                     err.c_str());
    }

    void execute(const vb_epp_op &op, const uint8_t *data, std::vector<uint8_t> &out)
    {
        uint8_t b = 0;
        switch (op.kind) {
        case OP_ADDR_WRITE:
            cycle(true, true, static_cast<uint8_t>(op.val), b);
            break;
        case OP_ADDR_READ:
            cycle(true, false, 0, b);
            out.push_back(b);
            break;
        case OP_DATA_WRITE:
            for (uint32_t i = 0; i < op.n; i++)
                cycle(false, true, data[i], b);
            break;
        case OP_DATA_READ:
            for (uint32_t i = 0; i < op.n; i++) {
                cycle(false, false, 0, b);
                out.push_back(b);
            }
            break;
        case OP_STATUS_READ:
            out.push_back(status_);
            break;
        case OP_STATUS_WRITE:
            // Ports differ (clear on writing 1 or 0); the drivers write both,
            // this one clears on a 1.
            if (op.val & kStatusTimeout)
                status_ &= static_cast<uint8_t>(~kStatusTimeout);
            break;
        case OP_CONTROL_WRITE:
            control_write(static_cast<uint8_t>(op.val));
            break;
        case OP_SPP_DATA_WRITE:
            spp_ = static_cast<uint8_t>(op.val);
            break;
        case OP_ECR_WRITE:
            ecr_ = static_cast<uint8_t>(op.val);
            break;
        case OP_DELAY:
            wait_ns(op.val);
            break;
        default:
            break;
        }
    }

    PinBank pins_;
    const PlutoFw *fw_ = nullptr;
    std::unique_ptr<PlutoModel> model_;
    PlutoIn in_;
    PlutoOut out_;
    uint64_t now_ = 0;
    uint8_t status_ = 0, control_ = 0x04, spp_ = 0, ecr_ = 0;
    bool stall_ = false, loading_ = false;
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
