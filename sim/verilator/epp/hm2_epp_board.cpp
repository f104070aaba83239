// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_epp_board.cpp - the virtual Mesa 7i43: the Verilated hm2 firmwares
// with the EPP front end (hm2_top_epp: SVST4_4, SV8, SVST2_4_7I47) behind
// a PC parallel port, and the board's CPLD that configures the FPGA
// (spec/hostmot2.md section 17.2; docs/vboard.md "7i43").
//
// While the FPGA is blank the CPLD answers EPP cycles at once: an address
// write selects register D0 (0 config data, 1 control); a data write to the
// control register drives PROG_B from D0 (0 clears the FPGA and restarts
// the configuration), to the data register clocks one bitstream byte in
// (the driver sends the .BIT 'e' chunk bit-reversed, as SelectMAP wants it;
// the board reverses it back); a read of the control register gives DONE in
// D0, of the data register the FPGA size (1 = 400K).  `--board 7i43` is the
// 400K board (3s400tq144), `--board 7i43-2` the 200K one (3s200tq144): its
// size bit reads 0 and it takes only images made for it (hm2/7i43-2/*.BIT),
// as a real 3s200 refuses a 3s400 bitstream.  After a whole image
// (fwimage.h) the board checks it and starts that firmware (DONE = 1); a
// bad image leaves it blank and says why on stderr.  Running, the firmware
// answers the EPP cycles pin-level; its `reconfig` pulse (data 0x5A at
// address 0x7F7F) hands the board back to the CPLD.
//
// Pins are the IDROM's I/O pins: 7i43 0..47 (P4 = 0..23, P3 = 24..47), 7i90
// 0..71 (P1, P2, P3).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "epp_fpga_board.h"
#include "fwimage.h"
#include "fwinfo.h"
#include "fwinfo_hm2_7i43_2_sv8.h"
#include "fwinfo_hm2_7i43_2_svst2_4_7i47.h"
#include "fwinfo_hm2_7i43_2_svst4_4.h"
#include "fwinfo_hm2_7i43_sv8.h"
#include "fwinfo_hm2_7i43_svst2_4_7i47.h"
#include "fwinfo_hm2_7i43_svst4_4.h"
#include "fwinfo_hm2_7i90_svst8_4.h"
#include "Vhm2_7i43_2_sv8.h"
#include "Vhm2_7i43_2_svst2_4_7i47.h"
#include "Vhm2_7i43_2_svst4_4.h"
#include "Vhm2_7i43_sv8.h"
#include "Vhm2_7i43_svst2_4_7i47.h"
#include "Vhm2_7i43_svst4_4.h"
#include "Vhm2_7i90_svst8_4.h"

namespace vb {
namespace {

// One ClockHigh period per clock(); ClockLow rises every `ratio` of them.
template <class V> class Hm2EppModelT final : public EppFpgaModelT<V> {
  public:
    explicit Hm2EppModelT(uint32_t ratio) : EppFpgaModelT<V>("hm2"), ratio_(ratio)
    {
        // start-up: the design runs a few ClockLow cycles after reset before
        // the host can reach it (the hm2 watchdog's power-up bite is over then)
        this->reset(4 * ratio_, 4 * ratio_);
    }
    void clock(const EppFpgaIn &in, EppFpgaOut &out) override
    {
        V &m = *this->m_;
        this->drive_epp(in);
        epp_set_io(m.io_in, in.io_in, in.io_in_hi);
        uint32_t phase = static_cast<uint32_t>(k_ % ratio_);
        m.clk_high = 1;
        if (phase == 0)
            m.clk_low = 1;
        m.eval();
        m.clk_high = 0;
        if (phase == (ratio_ - 1) / 2)
            m.clk_low = 0;
        m.eval();
        k_++;
        this->sample(out);
        out.reconfig = m.reconfig;
    }

  private:
    uint32_t ratio_;
    uint64_t k_ = 0;
};

struct Hm2EppFw {
    const FwInfo *info;
    std::unique_ptr<EppFpgaModel> (*make)(uint32_t ratio);
};

template <class V> std::unique_ptr<EppFpgaModel> make_model(uint32_t ratio)
{
    return std::make_unique<Hm2EppModelT<V>>(ratio);
}

// Each firmware is built for one board (its FwInfo's board): the 200K
// 7i43's are their own builds (hm2/7i43-2/, IDROM FPGASize 200).
const Hm2EppFw kFws[] = {
    {&kFwInfo_hm2_7i43_svst4_4, &make_model<Vhm2_7i43_svst4_4>},
    {&kFwInfo_hm2_7i43_sv8, &make_model<Vhm2_7i43_sv8>},
    {&kFwInfo_hm2_7i43_svst2_4_7i47, &make_model<Vhm2_7i43_svst2_4_7i47>},
    {&kFwInfo_hm2_7i43_2_svst4_4, &make_model<Vhm2_7i43_2_svst4_4>},
    {&kFwInfo_hm2_7i43_2_sv8, &make_model<Vhm2_7i43_2_sv8>},
    {&kFwInfo_hm2_7i43_2_svst2_4_7i47, &make_model<Vhm2_7i43_2_svst2_4_7i47>},
    {&kFwInfo_hm2_7i90_svst8_4, &make_model<Vhm2_7i90_svst8_4>},
};
constexpr int kNumFws = static_cast<int>(sizeof kFws / sizeof kFws[0]);

uint8_t reverse8(uint8_t b)
{
    b = static_cast<uint8_t>((b & 0xF0) >> 4 | (b & 0x0F) << 4);
    b = static_cast<uint8_t>((b & 0xCC) >> 2 | (b & 0x33) << 2);
    return static_cast<uint8_t>((b & 0xAA) >> 1 | (b & 0x55) << 1);
}

// The EPP hm2 boards: the two sizes of the 7i43 (FPGA part, CPLD size
// bit) and the 7i90, whose FPGA loads its firmware from the board's flash
// (no CPLD: it comes up running the first of its firmwares, or the one
// --firmware names, and reloads it on RECONFIG).
struct Hm2EppSize {
    const char *board;
    const char *fpga_part;
    uint8_t size_bit;
    uint32_t io_width;
    bool cpld;
    const char *how; // the reply to a configuration-port write
};
const Hm2EppSize kSizes[] = {
    {"7i43", "3s400tq144", 1, 48, true, "the 7i43 is configured through its CPLD over EPP"},
    {"7i43-2", "3s200tq144", 0, 48, true, "the 7i43 is configured through its CPLD over EPP"},
    {"7i90", "6slx9tqg144", 0, 72, false,
     "the 7i90 loads its firmware from its flash (mesaflash writes it)"},
};

class Hm2EppBoard final : public EppFpgaBoard {
  public:
    explicit Hm2EppBoard(const Hm2EppSize &size)
        : EppFpgaBoard(size.board, size.io_width, size.how, "IDROM CRC"), size_(size)
    {
        for (int i = 0; i < kNumFws; i++)
            if (std::strcmp(kFws[i].info->board, size.board) == 0)
                fws_.push_back(&kFws[i]);
        if (!size_.cpld && !fws_.empty())
            start(0); // the flash's firmware, at power-up
    }

    std::string fpga_part() const override { return size_.fpga_part; }
    uint32_t bus() const override { return VB_BUS_EPP_HM2; }
    uint32_t clock_low_hz() const override { return fw_ < 0 ? 0 : fws_[fw_]->info->clock_low_hz; }
    uint32_t clock_high_hz() const override
    {
        return fw_ < 0 ? 0 : fws_[fw_]->info->clock_high_hz;
    }
    std::vector<std::pair<std::string, std::string>>
    pin_names(const std::string &firmware) const override
    {
        std::vector<std::pair<std::string, std::string>> v;
        for (const Hm2EppFw *f : fws_)
            if (firmware == f->info->firmware)
                for (uint32_t p = 0; p < f->info->io_width; p++)
                    v.emplace_back(f->info->pins[p].label, f->info->pins[p].function);
        return v;
    }

  protected:
    int fw_count() const override { return static_cast<int>(fws_.size()); }
    const char *fw_name(int i) const override { return fws_[i]->info->firmware; }
    uint32_t fw_build_id(int i) const override { return fws_[i]->info->idrom_crc; }
    std::unique_ptr<EppFpgaModel> make_model(int i, uint64_t &step_ns) const override
    {
        const FwInfo &info = *fws_[i]->info;
        uint32_t ratio = info.clock_high_hz / info.clock_low_hz;
        step_ns = 1000000000ull / info.clock_high_hz;
        return fws_[i]->make(ratio ? ratio : 1);
    }

    void stepped() override
    {
        if (!out_.reconfig)
            return;
        if (!size_.cpld) { // reloads the same firmware from the flash
            std::fprintf(stderr, "vboard: %s: RECONFIG from firmware %s: reloaded from flash\n",
                         size_.board, fw_name(fw_));
            int i = fw_;
            unconfigure();
            start(i);
            return;
        }
        std::fprintf(stderr, "vboard: %s: RECONFIG from firmware %s: FPGA cleared\n",
                     size_.board, fw_name(fw_));
        unconfigure();
        cfg_.clear();
        cfg_done_ = false;
    }

    // The CPLD (FPGA blank).  A 7i90 is never blank; nothing answers.
    bool blank_cycle(bool addr, bool write, uint8_t w, uint8_t &r) override
    {
        if (!size_.cpld)
            return false;
        if (addr) {
            if (write)
                reg_ = w & 1u;
            else
                r = reg_;
            return true;
        }
        if (reg_ == 1) {
            if (!write) {
                r = fw_ < 0 ? 0 : 1; // DONE
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
            r = size_.size_bit; // 1: 400K part, 0: 200K part
            return true;
        }
        if (prog_b_ && !cfg_done_) {
            cfg_.push_back(reverse8(w));
            if (cfg_.size() == kFwImageSize) {
                cfg_done_ = true;
                configure_from(cfg_);
            }
        }
        return true;
    }

  private:
    const Hm2EppSize &size_;
    std::vector<const Hm2EppFw *> fws_; // the firmwares built for this board
    uint8_t reg_ = 0;
    bool prog_b_ = true, cfg_done_ = false;
    std::vector<uint8_t> cfg_;
};

std::vector<std::string> hm2_epp_boards()
{
    std::vector<std::string> v;
    for (const Hm2EppSize &s : kSizes)
        v.emplace_back(s.board);
    return v;
}

std::unique_ptr<Board> make_hm2_epp_board(const std::string &board)
{
    for (const Hm2EppSize &s : kSizes)
        if (board == s.board)
            return std::make_unique<Hm2EppBoard>(s);
    return nullptr;
}

} // namespace
} // namespace vb

extern const vb::BoardFactory vb_factory_hm2_epp;
const vb::BoardFactory vb_factory_hm2_epp = {vb::hm2_epp_boards, vb::make_hm2_epp_board};
