// SPDX-License-Identifier: GPL-2.0-or-later
//
// epp_port_board.h - a board behind a PC parallel port in EPP mode (the
// Pluto-P, the 7i43): the port's registers (spec/pluto.md section 1) and
// the pin-level EPP cycle engine, shared by the EPP boards.  A subclass
// provides the firmware side: one fine clock step, the EPP pins, and what
// answers while the FPGA is blank (nothing on a Pluto, the CPLD on a 7i43).
//
// An EPP cycle: the port sets nWrite and the data, asserts nAddrStr or
// nDataStr, runs the board until it acknowledges (nWait = 1), samples read
// data, releases the strobe and waits for the acknowledge to end.  No
// acknowledge within 10 us aborts the cycle and sets status bit 0; while the
// bit is set the port refuses further cycles (reads give 0xFF) until the
// host writes the status register with bit 0 set.
#ifndef VBOARD_EPP_PORT_BOARD_H
#define VBOARD_EPP_PORT_BOARD_H

#include <cstdint>
#include <string>
#include <vector>

#include "board.h"

namespace vb {

class EppPortBoard : public Board {
  public:
    int epp(const uint8_t *req, size_t len, std::vector<uint8_t> &out, std::string &err) override;
    int epp_stall(bool on, std::string &err) override;
    uint64_t now_ns() const override { return now_; }

  protected:
    static constexpr uint64_t kEppTimeoutNs = 10000; // PC port: ~10 us

    // The EPP signals the host drives (strobes/nWrite active low).
    struct Bus {
        uint8_t d = 0xFF;
        bool nwrite = true, ndatastr = true, naddrstr = true;
    };

    // ---- firmware side ----------------------------------------------------
    virtual bool fpga_running() const = 0;
    // Run one fine clock (the firmware's fastest) with bus_ on the pins.
    virtual void step() = 0;
    virtual uint64_t step_ns() const = 0;
    // The firmware's nWait (1 = acknowledge) and data output.
    virtual bool fpga_nwait() const = 0;
    virtual bool fpga_data(uint8_t &d) const = 0; // false: not driving
    // A blank FPGA: a cycle answered by something else (the 7i43's CPLD).
    // Return false when nothing answers (the cycle times out).
    virtual bool blank_cycle(bool addr, bool write, uint8_t w, uint8_t &r)
    {
        (void)addr, (void)write, (void)w, (void)r;
        return false;
    }
    // The control register changed (Pluto upload lines, nReset).
    virtual void control_written(uint8_t old, uint8_t v) { (void)old, (void)v; }

    // Let board time pass (clocks run while configured).
    void wait_ns(uint64_t ns);

    Bus bus_;
    uint64_t now_ = 0;
    uint8_t status_ = 0, control_ = 0x04, spp_ = 0, ecr_ = 0;
    bool stall_ = false;

  private:
    bool ack() const { return fpga_running() && !stall_ && fpga_nwait(); }
    bool cycle(bool addr, bool write, uint8_t w, uint8_t &r);
    void execute(const vb_epp_op &op, const uint8_t *data, std::vector<uint8_t> &out);
};

} // namespace vb

#endif // VBOARD_EPP_PORT_BOARD_H
