// SPDX-License-Identifier: GPL-2.0-or-later
//
// jtagtap.h - the JTAG port of a virtual board's Xilinx FPGA (Spartan-3/-6):
// an IEEE 1149.1 TAP driven by its lines (TCK, TMS, TDI in; TDO out), with
// the instructions a configuration tool uses (IR 6 bits): IDCODE 0x09
// (reset default), BYPASS 0x3F, JPROGRAM 0x0B (clear the configuration),
// CFG_IN 0x05 (configuration data, MSB of each byte first), JSTART 0x0C
// (startup: the collected bitstream configures the FPGA after 16 clocks in
// Run-Test/Idle).  The IR capture is ...01 with bit 4 INIT and bit 5 DONE.
// The board decides whether a bitstream configures it (the same checks as
// its bus path): a bad one leaves it blank, INIT low (CRC error).
#ifndef VBOARD_JTAGTAP_H
#define VBOARD_JTAGTAP_H

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vb {

// IDCODE of a Xilinx part by its .BIT name ("6slx9tqg144"); 0 if unknown.
uint32_t xilinx_idcode(const std::string &fpga_part);

class JtagTap {
  public:
    // configure(bits): 0 = the FPGA runs it; unconfigure(): JPROGRAM.
    JtagTap(uint32_t idcode, std::function<int(const std::vector<uint8_t> &)> configure,
            std::function<void()> unconfigure, std::function<bool()> done);
    // The lines now (bit 0 TCK, 1 TMS, 2 TDI); returns TDO.  A rising TCK
    // edge samples TMS/TDI; TDO changes on the falling edge.
    int lines(uint32_t levels);

  private:
    enum State {
        TLR, RTI, SEL_DR, CAP_DR, SH_DR, EX1_DR, PAU_DR, EX2_DR, UPD_DR,
        SEL_IR, CAP_IR, SH_IR, EX1_IR, PAU_IR, EX2_IR, UPD_IR
    };
    void rising(int tms, int tdi);
    void falling();
    static State next(State s, int tms);

    uint32_t idcode_;
    std::function<int(const std::vector<uint8_t> &)> configure_;
    std::function<void()> unconfigure_;
    std::function<bool()> done_;
    State st_ = TLR;
    int tck_ = 0, tdo_ = 1;
    uint8_t ir_ = 0x09, ir_shift_ = 0;
    uint64_t dr_ = 0;
    int dr_len_ = 0;
    std::vector<uint8_t> cfg_;
    uint8_t cfg_byte_ = 0;
    int cfg_bits_ = 0;
    bool init_ = true; // INIT high (no CRC error)
    int startup_clocks_ = -1;
};

} // namespace vb

#endif // VBOARD_JTAGTAP_H
