// SPDX-License-Identifier: GPL-2.0-or-later
//
// localbus.h - hm2 boards on a PCI-style local bus (5i20, 5i25, ...).
//
// A LocalBusBoard is blank until a firmware is loaded; then it owns one
// Verilated firmware model (LbModel<V>, localbus_model.h) that runs the
// clocks, the local-bus cycles and the pins.  The list of models comes from
// the generated lb_models.cpp (one entry per Verilated firmware).
#ifndef VBOARD_LOCALBUS_H
#define VBOARD_LOCALBUS_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "board.h"
#include "flashport.h"
#include "jtagtap.h"
#include "fwinfo.h"
#include "pins.h"

namespace vb {

// What the board needs from one running firmware.  Time is shared with the
// board: the model advances `now` and keeps its own edge schedule.
class LbModelBase {
  public:
    virtual ~LbModelBase() = default;
    // Execute every clock edge at or before t_ns.
    virtual void run_until(uint64_t t_ns) = 0;
    virtual uint64_t now_ns() const = 0;
    // Bursts: back to back ClockLow cycles (one per 32-bit word), reads
    // pipelined.  Writes end with the write landed in the registers.
    virtual int read(const vb_xfer *x, size_t n, std::vector<uint8_t> &out,
                     std::string &err) = 0;
    virtual void write(const vb_xfer *x, size_t n, const uint8_t *data) = 0;
    virtual int dump(bool on, const std::string &path, std::string &err) = 0;
};

struct LbEntry {
    const FwInfo *info;
    // A new model in reset at board time `start` (ns), wired to `pins`.
    std::unique_ptr<LbModelBase> (*make)(const FwInfo &info, PinBank &pins, uint64_t start);
};

extern const LbEntry kLbModels[];
extern const size_t kNumLbModels;

class LocalBusBoard final : public Board {
  public:
    // board: "5i20"; fails (nullptr from the factory) when no model of it
    // was Verilated.
    explicit LocalBusBoard(const std::string &board);
    ~LocalBusBoard() override;

    std::string name() const override { return board_; }
    std::string fpga_part() const override { return part_; }
    uint32_t bus() const override { return VB_BUS_LOCAL; }
    std::string firmware() const override { return fw_ ? fw_->firmware : ""; }
    uint32_t clock_low_hz() const override { return fw_ ? fw_->clock_low_hz : 0; }
    uint32_t clock_high_hz() const override { return fw_ ? fw_->clock_high_hz : 0; }
    std::vector<std::string> firmwares() const override;
    std::vector<std::pair<std::string, std::string>>
    pin_names(const std::string &firmware) const override;
    uint32_t firmware_clock_low_hz(const std::string &firmware) const override;
    PinBank &pins() override { return pins_; }
    uint64_t now_ns() const override { return model_ ? model_->now_ns() : now_; }
    void run_until(uint64_t t_ns) override;
    int config(uint32_t op, const uint8_t *bits, size_t len, vb_config_status &st,
               std::string &err) override;
    int load(const std::string &firmware, std::string &err) override;
    int lb_read(const vb_xfer *x, size_t n, std::vector<uint8_t> &out,
                std::string &err) override;
    int lb_write(const vb_xfer *x, size_t n, const uint8_t *data, std::string &err) override;
    int dump(bool on, const std::string &path, std::string &err) override;
    int set_model(const std::string &kind, const std::string &firmware,
                  std::string &err) override;
    std::string model() const override { return model_ ? (fast_ ? "fast" : "rtl") : ""; }
    int attach_flash(const std::string &path, const std::string &part, uint32_t speedup,
                     const std::string &firmware, std::string &err) override;
    bool flash_configured() const override;
    int jtag(uint32_t levels, uint32_t &tdo, std::string &err) override;

  private:
    const LbEntry *find(const std::string &firmware) const;
    // Whether the fast model runs firmware e under the present --model
    // (-ENOTSUP with the reason when --model fast and it cannot).
    int use_fast(const LbEntry &e, bool &fast, std::string &err) const;
    void start(const LbEntry &e, bool fast);
    void unconfigure();
    // The firmware an image selects: 0 and e, or -EINVAL (bad image) /
    // -ENODEV (another board's) with the reason.
    int match_image(const uint8_t *p, size_t n, const LbEntry *&e, std::string &err) const;
    static int check_image(void *ctx, const uint8_t *p, size_t n, std::string &err);
    // Configure from the flash (power-up, IPROG) starting at addr.
    void boot_from_flash(uint32_t addr, bool by_iprog);
    bool flash_reg(uint32_t addr) const;
    int flash_access(const vb_xfer &x, bool write, const uint8_t *data, std::vector<uint8_t> &out,
                     std::string &err);

    std::string board_, part_;
    PinBank pins_;
    const FwInfo *fw_ = nullptr;
    std::unique_ptr<LbModelBase> model_;
    // --model: rtl unless the owner says (vboard passes auto by default;
    // the in-process library keeps rtl until it asks for another)
    std::string model_kind_ = "rtl";
    bool fast_ = false;               // model_ is the fast model
    uint64_t now_ = 0; // board time while blank
    std::unique_ptr<SpiFlash> flash_;
    std::unique_ptr<FlashPort> port_;
    std::unique_ptr<JtagTap> tap_;
};

std::unique_ptr<Board> make_localbus_board(const std::string &board);
std::vector<std::string> localbus_boards();

} // namespace vb

#endif // VBOARD_LOCALBUS_H
