// SPDX-License-Identifier: GPL-2.0-or-later
//
// eth_board.h - Mesa Ethernet boards (7i92, 7i96S): the hm2 firmware on the
// Ethernet engine's internal local bus (a LocalBusBoard), the FPGA
// configuration flash and the LBP16 engine in front of both
// (docs/vboard.md "Ethernet boards").
//
// The FPGA configures itself from the flash: at power-up (when the flash
// holds a firmware and none is given on the command line) and on a reload
// (the ICAP sequence written to LBP16 space 6, 0x1E).  A flash image file
// (--flash FILE) keeps the flash across board restarts like the real chip.
#ifndef VBOARD_ETH_BOARD_H
#define VBOARD_ETH_BOARD_H

#include <memory>
#include <string>
#include <vector>

#include "board.h"
#include "lbp16.h"
#include "localbus.h"

namespace vb::eth {

// Flash geometry and layout of one board type.
struct FlashLayout {
    uint32_t size;          // bytes
    uint8_t id;             // what flash-ID register 8 reads
    uint32_t user_addr;     // user configuration (the firmware)
    uint32_t fallback_addr; // fallback configuration
    uint32_t erase_size;    // sector erase granularity
};

class EthBoard final : public Board {
  public:
    explicit EthBoard(const std::string &board);
    ~EthBoard() override;

    // Ethernet identity: the IP the board answers on (EEPROM), which also
    // seeds the MAC (00:60:1B + the IP's low three bytes).
    void set_ip(uint32_t ip_host_order);
    // Keep the flash in FILE (created erased when missing: fresh).  -errno
    // with a message.
    int attach_flash_file(const std::string &path, bool &fresh, std::string &err);
    // Power-up: configure from the flash's user area (a no-op when the
    // flash holds nothing valid: the board stays blank).
    void boot_from_flash();
    // One LBP16 datagram (lbp16.h).  true: send `reply`.
    bool lbp16(const uint8_t *pkt, size_t n, std::vector<uint8_t> &reply);
    Lbp16 &engine() { return *engine_; }
    const FlashLayout &flash_layout() const { return layout_; }
    const std::string &lbp16_name() const { return lbp16_name_; }

    // ---- Board ----
    std::string name() const override { return lb_.name(); }
    std::string fpga_part() const override { return lb_.fpga_part(); }
    uint32_t bus() const override { return lb_.bus(); }
    std::string firmware() const override { return lb_.firmware(); }
    uint32_t clock_low_hz() const override { return lb_.clock_low_hz(); }
    uint32_t clock_high_hz() const override { return lb_.clock_high_hz(); }
    std::vector<std::string> firmwares() const override { return lb_.firmwares(); }
    std::vector<std::pair<std::string, std::string>>
    pin_names(const std::string &firmware) const override
    {
        return lb_.pin_names(firmware);
    }
    uint32_t firmware_clock_low_hz(const std::string &firmware) const override
    {
        return lb_.firmware_clock_low_hz(firmware);
    }
    PinBank &pins() override { return lb_.pins(); }
    uint64_t now_ns() const override { return lb_.now_ns(); }
    void run_until(uint64_t t_ns) override { lb_.run_until(t_ns); }
    int config(uint32_t op, const uint8_t *bits, size_t len, vb_config_status &st,
               std::string &err) override;
    // The board configures itself from its flash (vboard --flash): a new
    // flash gets --firmware's .BIT at the fallback and user addresses (as a
    // board shipped with it holds it), then the FPGA boots from it.
    bool flash_configured() const override { return true; }
    int attach_flash(const std::string &path, const std::string &part, uint32_t speedup,
                     const std::string &firmware, std::string &err) override;
    // Program `firmware` into the flash and configure from it.
    int load(const std::string &firmware, std::string &err) override;
    int lb_read(const vb_xfer *x, size_t n, std::vector<uint8_t> &out,
                std::string &err) override
    {
        return lb_.lb_read(x, n, out, err);
    }
    int lb_write(const vb_xfer *x, size_t n, const uint8_t *data, std::string &err) override
    {
        return lb_.lb_write(x, n, data, err);
    }
    int dump(bool on, const std::string &path, std::string &err) override
    {
        return lb_.dump(on, path, err);
    }

  private:
    class Target;
    friend class Target;
    // Configure from the image at flash address `addr`; false (board
    // unchanged) with the reason when it holds no valid firmware.
    bool configure_from(uint32_t addr, std::string &why);
    // Write the built-in firmware's .BIT to the fallback and user areas.
    int program_builtin(const std::string &firmware, std::string &err);
    void reload();
    void save_flash();

    LocalBusBoard lb_;
    std::string lbp16_name_;
    FlashLayout layout_;
    std::vector<uint8_t> flash_;
    uint32_t flash_addr_ = 0;
    bool flash_dirty_ = false;
    std::string flash_path_;
    std::vector<uint16_t> icap_;
    bool reload_pending_ = false, reset_pending_ = false;
    uint32_t ip_ = 0x7F000001;
    std::unique_ptr<Target> target_;
    std::unique_ptr<Lbp16> engine_;
};

// The .BIT file the build writes for a built-in firmware (tools/vbfw).
std::vector<uint8_t> builtin_bitfile(const std::string &board, const std::string &firmware,
                                     const std::string &part, uint32_t idrom_crc);

std::unique_ptr<Board> make_eth_board(const std::string &board);
std::vector<std::string> eth_boards();

} // namespace vb::eth

#endif // VBOARD_ETH_BOARD_H
