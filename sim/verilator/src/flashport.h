// SPDX-License-Identifier: GPL-2.0-or-later
//
// flashport.h - what a Spartan-6 hm2 board adds around its configuration
// flash (docs/vboard.md "Configuration flash"):
//
//  * the SPI access registers the hm2 firmware of flash-configured PCI
//    boards has in its null page (the ones mesaflash drives):
//      0x0070  control: write bit 0 = /CS level (1 = deselected);
//              read bit 2 = DAV (the last byte has been shifted), bit 0 = /CS
//      0x0074  data: a write shifts one byte out (8 SCK at ClockLow / 2) and
//              clears DAV; a read returns the byte shifted in
//  * the ICAP port at 0x0078: writes are 16-bit configuration words (sync
//    0xAA99 0x5566, type-1 packets to GENERAL1..4 and CMD; CMD = IPROG
//    reconfigures from the flash); a read returns 0x1CAB1CAB, the cookie
//    mesaflash 3.4.6 checks before --reload (spec/hostmot2.md
//    "Configuration flash");
//  * 0x007C (the virtual board's own, not Mesa's): a read returns the boot
//    status (Spartan-6 BOOTSTS bits: 0 valid, 1 fallback used, 2 started by
//    IPROG, 4 ID error (image for another board), 5 CRC error);
//  * the FPGA's own configuration from the flash: at power-up and on IPROG
//    it reads address 0 (or the IPROG address): a boot block (sync word and
//    packets that set the MultiBoot and fallback addresses, then IPROG) is
//    followed; the image found there is configured, and when it is bad the
//    fallback image is, as a Spartan-6 does.
#ifndef VBOARD_FLASHPORT_H
#define VBOARD_FLASHPORT_H

#include <cstdint>
#include <string>
#include <vector>

#include "spiflash.h"

namespace vb {

// The layout Mesa's Spartan-6 boards use.
constexpr uint32_t kFlashBootAddr = 0x000000;
constexpr uint32_t kFlashFallbackAddr = 0x010000;
constexpr uint32_t kFlashUserAddr = 0x100000; // mesaflash's user area (16 Mbit)
constexpr uint32_t kFlashRegCtrl = 0x0070;
constexpr uint32_t kFlashRegData = 0x0074;
constexpr uint32_t kFlashRegIcap = 0x0078;
constexpr uint32_t kFlashRegBootsts = 0x007C; // virtual board only
constexpr uint32_t kIcapCookie = 0x1CAB1CAB;

enum : uint32_t {
    BOOTSTS_VALID = 1u << 0,
    BOOTSTS_FALLBACK = 1u << 1,
    BOOTSTS_IPROG = 1u << 2,
    BOOTSTS_ID_ERROR = 1u << 4,
    BOOTSTS_CRC_ERROR = 1u << 5,
};

// The boot block mesaflash writes (recorded in tests/data/eth/mesaflash):
// padding, sync, type-1 writes (0x0F = 0xFFFF, GENERAL1..4 = MultiBoot
// address `user` and `fallback` with read opcode 0x0B, CMD = 0, 0x18 =
// 0x2100, 0x10 = 0x001F), CMD = IPROG, seven NOOPs: 64 bytes.  `bytes` are as stored in the flash (big-endian 16-bit words).
std::vector<uint8_t> flash_boot_block(uint32_t user, uint32_t fallback);

// What a configuration attempt decided.
struct BootResult {
    bool configured = false;
    uint32_t from = 0;          // flash address of the image configured
    std::vector<uint8_t> image; // its bytes (a vboard firmware image)
    uint32_t bootsts = 0;
    std::string log;            // what was tried, for --log and errors
};

// Checks an image at a flash address; 0 when the board can run it, else
// -errno with the reason.
using ImageCheck = int (*)(void *ctx, const uint8_t *p, size_t n, std::string &err);

class FlashPort {
  public:
    explicit FlashPort(SpiFlash &flash) : flash_(flash) {}

    // Register access; `now` is board time, `sck_ns` one SCK period.
    uint32_t read(uint32_t addr, uint64_t now);
    void write(uint32_t addr, uint32_t value, uint64_t now, uint64_t sck_ns);
    // An IPROG came through ICAP (cleared by take_iprog()).
    bool take_iprog(uint32_t &addr);

    // Configure from the flash the way the FPGA does, starting at `addr`.
    BootResult boot(uint32_t addr, bool by_iprog, ImageCheck check, void *ctx);
    void set_bootsts(uint32_t s) { bootsts_ = s; }

  private:
    SpiFlash &flash_;
    bool cs_high_ = true;
    uint8_t rx_ = 0xFF;
    uint64_t dav_at_ = 0;
    // ICAP packet state
    bool synced_ = false;
    int want_reg_ = -1; // register a type-1 write header announced
    uint16_t general_[5] = {0, 0, 0, 0, 0};
    bool iprog_ = false;
    uint32_t bootsts_ = 0;
};

} // namespace vb

#endif // VBOARD_FLASHPORT_H
