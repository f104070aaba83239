// SPDX-License-Identifier: GPL-2.0-or-later
//
// localbus.cpp - hm2 local-bus boards: blank state, configuration port and
// firmware checks, delegation of time and bus cycles to the running model.
#include "localbus.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "fwimage.h"

namespace vb {

namespace {
uint32_t board_io_width(const std::string &board)
{
    uint32_t w = 0;
    for (size_t i = 0; i < kNumLbModels; i++)
        if (board == kLbModels[i].info->board)
            w = std::max(w, kLbModels[i].info->io_width);
    return w;
}

std::string board_part(const std::string &board)
{
    for (size_t i = 0; i < kNumLbModels; i++)
        if (board == kLbModels[i].info->board)
            return kLbModels[i].info->fpga_part;
    return "";
}

std::string join(const std::vector<std::string> &v)
{
    std::string s;
    for (const std::string &e : v)
        s += (s.empty() ? "" : ", ") + e;
    return s.empty() ? "none" : s;
}

void fill_status(vb_config_status &st, const std::string &fw)
{
    std::memset(&st, 0, sizeof st);
    st.done = fw.empty() ? 0 : 1;
    st.init = 1;
    std::strncpy(st.firmware, fw.c_str(), sizeof st.firmware - 1);
}
} // namespace

LocalBusBoard::LocalBusBoard(const std::string &board)
    : board_(board), part_(board_part(board)), pins_(board_io_width(board))
{
}

LocalBusBoard::~LocalBusBoard() = default;

std::vector<std::string> LocalBusBoard::firmwares() const
{
    std::vector<std::string> v;
    for (size_t i = 0; i < kNumLbModels; i++)
        if (board_ == kLbModels[i].info->board)
            v.push_back(kLbModels[i].info->firmware);
    return v;
}

std::vector<std::pair<std::string, std::string>>
LocalBusBoard::pin_names(const std::string &firmware) const
{
    std::vector<std::pair<std::string, std::string>> v;
    if (const LbEntry *e = find(firmware))
        for (uint32_t p = 0; p < e->info->io_width; p++)
            v.emplace_back(e->info->pins[p].label, e->info->pins[p].function);
    return v;
}

const LbEntry *LocalBusBoard::find(const std::string &firmware) const
{
    for (size_t i = 0; i < kNumLbModels; i++)
        if (board_ == kLbModels[i].info->board && firmware == kLbModels[i].info->firmware)
            return &kLbModels[i];
    return nullptr;
}

void LocalBusBoard::run_until(uint64_t t)
{
    if (model_) {
        model_->run_until(t);
        return;
    }
    if (t <= now_)
        return;
    // Blank: only the outside world moves (quadrature sources).
    pins_.run_events(t);
    now_ = t;
}

void LocalBusBoard::unconfigure()
{
    if (model_) {
        now_ = model_->now_ns();
        model_.reset();
    }
    fw_ = nullptr;
    pins_.release_fpga(now_);
}

void LocalBusBoard::start(const LbEntry &e)
{
    unconfigure();
    fw_ = e.info;
    model_ = e.make(*e.info, pins_, now_);
}

int LocalBusBoard::load(const std::string &firmware, std::string &err)
{
    const LbEntry *e = find(firmware);
    if (!e) {
        err = "firmware " + firmware + " is not built into this vboard for board " + board_ +
              " (built: " + join(firmwares()) + ")";
        return -ENOENT;
    }
    start(*e);
    return 0;
}

int LocalBusBoard::config(uint32_t op, const uint8_t *bits, size_t len, vb_config_status &st,
                          std::string &err)
{
    switch (op) {
    case VB_CONFIG_STATUS:
        break;
    case VB_CONFIG_RESET:
        unconfigure();
        break;
    case VB_CONFIG_PROGRAM: {
        // The image is checked before anything changes: a bad request is
        // not applied (the protocol's error rule), so a configured board
        // keeps its firmware and a blank one stays blank.  (The drivers
        // reset the board before programming, as on real hardware.)
        std::vector<BuiltFw> built;
        std::vector<const LbEntry *> entries;
        for (size_t i = 0; i < kNumLbModels; i++)
            if (board_ == kLbModels[i].info->board) {
                built.push_back({kLbModels[i].info->firmware, kLbModels[i].info->idrom_crc});
                entries.push_back(&kLbModels[i]);
            }
        int rc = match_fw_image(bits, len, board_, built, "IDROM CRC", err);
        const LbEntry *e = rc >= 0 ? entries[static_cast<size_t>(rc)] : nullptr;
        if (rc < 0) {
            fill_status(st, firmware());
            err = board_ + ": configuration failed, board " +
                  (configured() ? "keeps firmware " + firmware() : std::string("stays blank")) +
                  ": " + err;
            return rc;
        }
        start(*e);
        break;
    }
    default:
        err = "config: unknown operation " + std::to_string(op) +
              " (0 status, 1 reset, 2 program)";
        fill_status(st, firmware());
        return -EINVAL;
    }
    fill_status(st, firmware());
    return 0;
}

int LocalBusBoard::lb_read(const vb_xfer *x, size_t n, std::vector<uint8_t> &out,
                           std::string &err)
{
    if (!model_) {
        err = "board " + board_ + " is not configured (blank FPGA): no local-bus target";
        return -ENODEV;
    }
    return model_->read(x, n, out, err);
}

int LocalBusBoard::lb_write(const vb_xfer *x, size_t n, const uint8_t *data, std::string &err)
{
    if (!model_) {
        err = "board " + board_ + " is not configured (blank FPGA): no local-bus target";
        return -ENODEV;
    }
    model_->write(x, n, data);
    return 0;
}

int LocalBusBoard::dump(bool on, const std::string &path, std::string &err)
{
    if (!model_) {
        if (!on)
            return 0;
        err = "dump: board " + board_ + " is blank: no firmware to trace";
        return -ENODEV;
    }
    return model_->dump(on, path, err);
}

std::vector<std::string> localbus_boards()
{
    std::vector<std::string> v;
    for (size_t i = 0; i < kNumLbModels; i++)
        if (std::find(v.begin(), v.end(), kLbModels[i].info->board) == v.end())
            v.push_back(kLbModels[i].info->board);
    return v;
}

std::unique_ptr<Board> make_localbus_board(const std::string &board)
{
    std::vector<std::string> known = localbus_boards();
    if (std::find(known.begin(), known.end(), board) == known.end())
        return nullptr;
    return std::make_unique<LocalBusBoard>(board);
}

} // namespace vb

// The family's factory, listed in the generated vboard_factories.cpp.
extern const vb::BoardFactory vb_factory_localbus;
const vb::BoardFactory vb_factory_localbus = {vb::localbus_boards, vb::make_localbus_board};
