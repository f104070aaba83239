// SPDX-License-Identifier: GPL-2.0-or-later
//
// spiflash.h - a serial (SPI) NOR configuration flash as the FPGA boards
// carry it (5i25/6i25: an M25P16), modelled at the command level: JEDEC ID,
// electronic signature, status register (WIP, WEL, block protect), read,
// fast read, page program, sector erase, bulk erase, with the part's
// typical busy times in board time (docs/vboard.md "Configuration flash").
//
// Storage is a byte array, either private memory or a file mapped shared
// (vboard --flash FILE): every program or erase lands in the file at once,
// so a board killed mid-operation leaves the flash as a power loss would.
// A page program applies its bytes when the part's program time is over; a
// sector erase clears the first half of the sector at once and the rest when
// its time is over, so an interrupted one leaves a half-erased sector.
#ifndef VBOARD_SPIFLASH_H
#define VBOARD_SPIFLASH_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vb {

struct FlashPart {
    const char *name;     // "m25p16"
    uint8_t jedec[3];     // manufacturer, memory type, capacity (RDID 0x9F)
    uint8_t signature;    // electronic signature (RES 0xAB)
    uint32_t size;        // bytes
    uint32_t sector;      // erase unit (SE 0xD8)
    uint32_t page;        // program unit (PP 0x02)
    uint64_t t_pp_ns;     // typical page program time
    uint64_t t_se_ns;     // typical sector erase time
    uint64_t t_be_ns;     // typical bulk erase time
    uint64_t t_w_ns;      // typical write-status-register time
};

// The known parts; nullptr when `name` is none of them.
const FlashPart *flash_part(const std::string &name);
std::string flash_part_names();

class SpiFlash {
  public:
    SpiFlash() = default;
    ~SpiFlash();
    SpiFlash(const SpiFlash &) = delete;
    SpiFlash &operator=(const SpiFlash &) = delete;

    // Storage in memory (erased), or a file: created erased when missing
    // (`created` says so), else it must have exactly the part's size.
    int open(const FlashPart &part, const std::string &path, bool &created, std::string &err);
    // Busy times are divided by this (tests; 1 = the part's timing).
    void set_speedup(uint32_t s) { speedup_ = s ? s : 1; }

    // The bus.  select(true) = /S low (a command starts); select(false) =
    // /S high (a write command executes).  transfer() shifts one byte in
    // and returns the byte shifted out.  `now` is board time in ns.
    void select(bool active, uint64_t now);
    uint8_t transfer(uint8_t mosi, uint64_t now);

    // Finish whatever operation is due by `now`.
    void sync(uint64_t now);
    bool busy(uint64_t now);
    const FlashPart &part() const { return *part_; }
    // Direct access (the FPGA's own configuration reads, factory contents).
    const uint8_t *data() const { return mem_; }
    void poke(uint32_t addr, const uint8_t *p, size_t n);

  private:
    struct Pending {
        enum Kind { NONE, PROGRAM, ERASE, STATUS } kind = NONE;
        uint64_t done_ns = 0;
        uint32_t addr = 0, len = 0;
        std::vector<uint8_t> bytes; // PROGRAM: a page image (0xFF = keep)
        uint8_t status = 0;         // STATUS: the new BP bits
    };
    bool is_protected(uint32_t addr, uint32_t len) const;
    void execute(uint64_t now);
    void start(Pending p, uint64_t busy_ns, uint64_t now);
    uint8_t status_byte(uint64_t now);

    const FlashPart *part_ = nullptr;
    uint8_t *mem_ = nullptr;
    size_t map_len_ = 0;
    bool mapped_ = false;
    std::vector<uint8_t> own_;
    uint32_t speedup_ = 1;

    // bus state of the command in progress
    bool selected_ = false;
    std::vector<uint8_t> cmd_; // every byte shifted in since /S went low
    uint32_t read_addr_ = 0;
    // part state
    bool wel_ = false;
    uint8_t bp_ = 0; // block-protect bits (status bits 4..2)
    Pending pending_;
};

} // namespace vb

#endif // VBOARD_SPIFLASH_H
