// SPDX-License-Identifier: GPL-2.0-or-later
//
// jtagtap.cpp - a Xilinx FPGA's JTAG port on a virtual board (jtagtap.h).
#include "jtagtap.h"

#include <utility>

namespace vb {

namespace {
constexpr uint8_t kCfgIn = 0x05, kIdcode = 0x09, kJprogram = 0x0B, kJstart = 0x0C;
constexpr int kStartupClocks = 16;
} // namespace

uint32_t xilinx_idcode(const std::string &part)
{
    // bits 27..0 of the parts on Mesa boards (the host's table: host/driver/jtag/jtag.c)
    static const std::pair<const char *, uint32_t> ids[] = {
        {"6slx9", 0x04001093u},  {"6slx16", 0x04002093u}, {"6slx25", 0x04004093u},
        {"3s200", 0x01414093u},  {"3s400", 0x0141C093u},  {"3s1000", 0x01428093u},
        {"3s1500", 0x01434093u}, {"3s2000", 0x01440093u},
    };
    for (const auto &p : ids) {
        std::string n = p.first;
        // the name, then the package: "6slx9tqg144", not "6slx16..." for "6slx1"
        if (part.compare(0, n.size(), n) == 0 && part.size() > n.size() &&
            !(part[n.size()] >= '0' && part[n.size()] <= '9'))
            return p.second;
    }
    return 0;
}

JtagTap::JtagTap(uint32_t idcode, std::function<int(const std::vector<uint8_t> &)> configure,
                 std::function<void()> unconfigure, std::function<bool()> done)
    : idcode_(idcode), configure_(std::move(configure)), unconfigure_(std::move(unconfigure)),
      done_(std::move(done))
{
}

JtagTap::State JtagTap::next(State s, int tms)
{
    static const State t[16][2] = {
        {RTI, TLR},       {RTI, SEL_DR},    {CAP_DR, SEL_IR}, {SH_DR, EX1_DR},
        {SH_DR, EX1_DR},  {PAU_DR, UPD_DR}, {PAU_DR, EX2_DR}, {SH_DR, UPD_DR},
        {RTI, SEL_DR},    {CAP_IR, TLR},    {SH_IR, EX1_IR},  {SH_IR, EX1_IR},
        {PAU_IR, UPD_IR}, {PAU_IR, EX2_IR}, {SH_IR, UPD_IR},  {RTI, SEL_DR},
    };
    return t[s][tms ? 1 : 0];
}

void JtagTap::rising(int tms, int tdi)
{
    // the current state's action, then the transition
    switch (st_) {
    case TLR: ir_ = kIdcode; break;
    case RTI:
        if (ir_ == kJstart && startup_clocks_ >= 0 && ++startup_clocks_ == kStartupClocks) {
            init_ = configure_(cfg_) == 0;
            cfg_.clear();
        }
        break;
    case CAP_IR:
        ir_shift_ = static_cast<uint8_t>(0x01u | (init_ ? 0x10u : 0u) | (done_() ? 0x20u : 0u));
        break;
    case SH_IR: ir_shift_ = static_cast<uint8_t>((ir_shift_ >> 1) | (tdi ? 0x20u : 0u)); break;
    case CAP_DR:
        if (ir_ == kIdcode) {
            dr_ = idcode_;
            dr_len_ = 32;
        } else {
            dr_ = 0;
            dr_len_ = 1;
        }
        break;
    case SH_DR:
        if (ir_ == kCfgIn) {
            cfg_byte_ = static_cast<uint8_t>(cfg_byte_ << 1 | (tdi ? 1 : 0));
            if (++cfg_bits_ == 8) {
                cfg_.push_back(cfg_byte_);
                cfg_bits_ = 0;
            }
        } else {
            dr_ = dr_ >> 1 | (static_cast<uint64_t>(tdi ? 1 : 0) << (dr_len_ - 1));
        }
        break;
    case UPD_IR:
        ir_ = ir_shift_ & 0x3F;
        if (ir_ == kJprogram) {
            unconfigure_();
            cfg_.clear();
            cfg_bits_ = 0;
            init_ = true;
        } else if (ir_ == kCfgIn) {
            cfg_bits_ = 0;
        } else if (ir_ == kJstart) {
            startup_clocks_ = 0;
        }
        break;
    default: break;
    }
    if (st_ == UPD_IR && ir_ != kJstart)
        startup_clocks_ = -1;
    st_ = next(st_, tms);
}

void JtagTap::falling()
{
    if (st_ == SH_IR)
        tdo_ = ir_shift_ & 1;
    else if (st_ == SH_DR)
        tdo_ = static_cast<int>(dr_ & 1);
    else
        tdo_ = 1;
}

int JtagTap::lines(uint32_t levels)
{
    int tck = levels & 1u, tms = (levels >> 1) & 1u, tdi = (levels >> 2) & 1u;
    if (tck && !tck_)
        rising(tms, tdi);
    else if (!tck && tck_)
        falling();
    tck_ = tck;
    return tdo_;
}

} // namespace vb
