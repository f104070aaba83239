// SPDX-License-Identifier: GPL-2.0-or-later
//
// fwinfo.h - facts about one Verilated firmware, generated per firmware by
// tools/vbfw --header from hm2gen's JSON (so the board and the .BIT file it
// accepts come from the same description).
#ifndef VBOARD_FWINFO_H
#define VBOARD_FWINFO_H

#include <cstdint>

namespace vb {

// One I/O pin of a firmware: its connector label ("P2-05") and the module
// function routed to it ("Encoder 0 B"; "" for a plain GPIO).
struct PinName {
    const char *label;
    const char *function;
};

struct FwInfo {
    const char *board;      // "5i20"
    const char *firmware;   // "SVST8_4"
    const char *fpga_part;  // "2s200pq208"
    uint32_t clock_low_hz;
    uint32_t clock_high_hz;
    uint32_t io_width;
    uint32_t idrom_crc;     // CRC-32 of the IDROM words (fwimage.h)
    // Some module has logic on ClockHigh (PWMGen).  When none has, the
    // board skips the ClockHigh-only edges: nothing could see them.
    bool uses_clock_high;
    const PinName *pins;    // io_width entries, in IO order
};

} // namespace vb

#endif // VBOARD_FWINFO_H
