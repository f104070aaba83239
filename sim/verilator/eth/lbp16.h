// SPDX-License-Identifier: GPL-2.0-or-later
//
// lbp16.h - the LBP16 command engine of a virtual Mesa Ethernet board
// (spec/hostmot2.md 17.3, docs/vboard.md "Ethernet boards").
//
// One datagram holds a sequence of commands; they run in order and the
// board sends one reply holding the read data of every read command, back
// to back.  A datagram without reads, or one in which a command fails
// (parse error, bad space/size/address, refused write), gets no reply; the
// failure is counted in the LBP16 status space (space 6) as Mesa's
// firmware counts it.  The commands before the failing one have run.
//
// The engine owns the small memories (EEPROM, Ethernet-chip registers,
// timers/scratch, status and board information); the hm2 register space,
// the FPGA flash and the reset/reconfigure actions belong to the board
// behind it (Lbp16Target), so the engine can be driven by a fake target in
// the unit tests and the fuzz target.
#ifndef VBOARD_ETH_LBP16_H
#define VBOARD_ETH_LBP16_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vb::eth {

// Address spaces (command bits 12..10).
enum Space : unsigned {
    kSpaceHm2 = 0,
    kSpaceEthChip = 1,
    kSpaceEeprom = 2,
    kSpaceFlash = 3,
    kSpaceTimers = 4,
    kSpaceStatus = 6,
    kSpaceInfo = 7,
};

// Space 6 (LBP16RW) word offsets.
enum StatusReg : unsigned {
    kStErrorFlags = 0x00,
    kStParseErrors = 0x02,
    kStMemErrors = 0x04,
    kStWriteErrors = 0x06,
    kStRxPackets = 0x08,
    kStRxUdp = 0x0A,
    kStRxBad = 0x0C,
    kStTxPackets = 0x0E,
    kStTxUdp = 0x10,
    kStTxBad = 0x12,
    kStLedMode = 0x14,
    kStDebugLed = 0x16,
    kStScratch = 0x18,
    kStWriteEnable = 0x1A,
    kStReset = 0x1C,
    kStReconfig = 0x1E,
};
constexpr uint16_t kWriteEnableKey = 0x5A03;

// What the board behind the engine provides.  Every method returns false
// (and the engine counts a memory error) when the access is impossible.
class Lbp16Target {
  public:
    virtual ~Lbp16Target() = default;
    // hm2 register space: `count` 32-bit words from `addr`, incrementing
    // or all at the same address.
    virtual bool hm2_read(uint32_t addr, unsigned count, bool inc, uint8_t *out) = 0;
    virtual bool hm2_write(uint32_t addr, unsigned count, bool inc, const uint8_t *data) = 0;
    // FPGA flash (space 3): register 0 address, 4 data (auto-advancing),
    // 8 flash ID, 0xC sector erase.  `enabled`: the write enable key was
    // written in this datagram.
    virtual bool flash_read(uint32_t reg, uint32_t &value) = 0;
    virtual bool flash_write(uint32_t reg, uint32_t value, bool enabled) = 0;
    // Board time in us (the timer space's time stamp).
    virtual uint64_t now_us() const = 0;
    // Let `us` microseconds pass before the next command (timer space 0x02).
    virtual void wait_us(unsigned us) = 0;
    // Reset request (space 6, 0x1C): restart the firmware.
    virtual void reset() = 0;
    // A word written to the reconfiguration (ICAP) port, space 6, 0x1E.
    virtual void icap_word(uint16_t w) = 0;
};

// The board's identity in spaces 2 and 7.
struct Lbp16Identity {
    std::string board_name;          // "7I96S": space 7 0x00, NUL padded
    std::array<uint8_t, 6> mac{};    // printable order, MAC[0] first
    uint32_t ip = 0;                 // as the EEPROM holds it (host order)
    uint16_t ip_source = 1;          // space 7 0x14: 1 = IP address from EEPROM
    uint16_t fw_version = 16;        // space 7 0x12 (> 14: reload through 0x1E)
    uint8_t flash_log2_page = 8;     // info area of space 3
    uint8_t flash_log2_erase = 16;
};

class Lbp16 {
  public:
    Lbp16(Lbp16Target &t, const Lbp16Identity &id);

    // Run one datagram.  true: `reply` (cleared first) must be sent back;
    // false: `reply` is empty.
    bool handle(const uint8_t *pkt, size_t n, std::vector<uint8_t> &reply);
    // Counters the transport updates (replies sent, send failures).
    void count_tx(bool ok);
    // Read one 16-bit word of a small space (tests, logs).
    uint16_t word(unsigned space, unsigned addr) const;
    // Human-readable reason of the last failed datagram ("" if none yet).
    const std::string &last_error() const { return last_error_; }

  private:
    struct Cmd {
        bool write, has_addr, info, inc;
        unsigned space, size, count;
    };
    enum class Fail { kNone, kParse, kMemory, kWrite };

    bool run_datagram(const uint8_t *pkt, size_t n, std::vector<uint8_t> &reply);
    Fail run(const Cmd &c, uint32_t addr, const uint8_t *data, std::vector<uint8_t> &reply);
    Fail small_read(const Cmd &c, uint32_t addr, std::vector<uint8_t> &reply);
    Fail small_write(const Cmd &c, uint32_t addr, const uint8_t *data);
    Fail info_read(const Cmd &c, uint32_t addr, std::vector<uint8_t> &reply);
    Fail flash(const Cmd &c, uint32_t addr, const uint8_t *data, std::vector<uint8_t> &reply);
    bool store_word(unsigned space, uint32_t addr, uint16_t v);
    void fail(Fail f, const std::string &why);
    std::vector<uint16_t> *mem(unsigned space);
    const std::vector<uint16_t> *mem(unsigned space) const;
    void bump(unsigned reg);

    Lbp16Target &t_;
    Lbp16Identity id_;
    std::vector<uint16_t> eth_chip_, eeprom_, timers_, status_, info_;
    std::array<uint32_t, 8> ptr_{}; // each space's address pointer
    bool write_enabled_ = false;    // key seen in the current datagram
    std::string last_error_;
};

// Byte range of each space (0 for spaces that do not exist).
uint32_t lbp16_space_range(unsigned space);

} // namespace vb::eth

#endif // VBOARD_ETH_LBP16_H
