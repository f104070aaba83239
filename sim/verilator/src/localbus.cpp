// SPDX-License-Identifier: GPL-2.0-or-later
//
// localbus.cpp - hm2 local-bus boards: blank state, configuration port and
// firmware checks, delegation of time and bus cycles to the running model.
#include "localbus.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "fast_idroms.h"
#include "fast_model.h"
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

uint32_t LocalBusBoard::firmware_clock_low_hz(const std::string &firmware) const
{
    const LbEntry *e = find(firmware);
    return e ? e->info->clock_low_hz : 0;
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

int LocalBusBoard::set_model(const std::string &kind, const std::string &firmware,
                             std::string &err)
{
    if (kind != "rtl" && kind != "fast" && kind != "auto") {
        err = "model '" + kind + "' is not rtl, fast or auto";
        return -EINVAL;
    }
    std::string old = model_kind_;
    model_kind_ = kind;
    const LbEntry *e = firmware.empty() ? nullptr : find(firmware);
    bool fast = false;
    if (e && use_fast(*e, fast, err) < 0) {
        model_kind_ = old;
        return -ENOTSUP;
    }
    return 0;
}

int LocalBusBoard::use_fast(const LbEntry &e, bool &fast, std::string &err) const
{
    fast = false;
    if (model_kind_ == "rtl")
        return 0;
    const uint32_t *idrom = fast::find_idrom(e.info->board, e.info->firmware);
    std::string why = idrom ? fast::fast_coverage(idrom) : "its IDROM is not in this build";
    if (why.empty()) {
        fast = true;
        return 0;
    }
    if (model_kind_ == "auto")
        return 0;
    err = "--model fast: firmware " + std::string(e.info->firmware) + " on " + board_ + ": " + why;
    return -ENOTSUP;
}

void LocalBusBoard::start(const LbEntry &e, bool fast)
{
    unconfigure();
    fw_ = e.info;
    fast_ = false;
    if (fast) {
        std::string err;
        model_ = fast::make_fast_model(*e.info, fast::find_idrom(e.info->board, e.info->firmware),
                                       pins_, now_, err);
        fast_ = model_ != nullptr;
        if (!model_) // use_fast() checked the firmware: not reached
            std::fprintf(stderr, "vboard: %s; running the RTL model\n", err.c_str());
    }
    if (!model_)
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
    bool fast = false;
    int rc = use_fast(*e, fast, err);
    if (rc < 0)
        return rc;
    start(*e, fast);
    return 0;
}

int LocalBusBoard::match_image(const uint8_t *p, size_t n, const LbEntry *&e,
                               std::string &err) const
{
    std::vector<BuiltFw> built;
    std::vector<const LbEntry *> entries;
    for (size_t i = 0; i < kNumLbModels; i++)
        if (board_ == kLbModels[i].info->board) {
            built.push_back({kLbModels[i].info->firmware, kLbModels[i].info->idrom_crc});
            entries.push_back(&kLbModels[i]);
        }
    FwImage img;
    int rc = parse_fw_image(p, n, img, err);
    if (rc < 0)
        return rc;
    rc = match_fw_image(p, n, board_, built, "IDROM CRC", err);
    if (rc < 0)
        return img.board != board_ ? -ENODEV : rc;
    e = entries[static_cast<size_t>(rc)];
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
        const LbEntry *e = nullptr;
        int rc = match_image(bits, len, e, err);
        if (rc < 0) {
            fill_status(st, firmware());
            err = board_ + ": configuration failed, board " +
                  (configured() ? "keeps firmware " + firmware() : std::string("stays blank")) +
                  ": " + err;
            return rc == -ENODEV ? -EINVAL : rc;
        }
        bool fast = false;
        rc = use_fast(*e, fast, err);
        if (rc < 0) {
            fill_status(st, firmware());
            return rc;
        }
        start(*e, fast);
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

bool LocalBusBoard::flash_reg(uint32_t addr) const
{
    return port_ && addr >= kFlashRegCtrl && addr <= kFlashRegBootsts;
}

// One xfer that touches the flash registers, word by word; each word takes
// one ClockLow cycle of board time.
int LocalBusBoard::flash_access(const vb_xfer &x, bool write, const uint8_t *data,
                                std::vector<uint8_t> &out, std::string &err)
{
    uint64_t cycle = fw_->clock_low_hz ? 1000000000ull / fw_->clock_low_hz : 30;
    for (uint32_t off = 0; off < x.size; off += 4) {
        uint32_t a = x.addr + off;
        uint64_t now = model_->now_ns();
        if (write) {
            uint32_t v = 0;
            std::memcpy(&v, data + off, 4);
            if (flash_reg(a)) {
                port_->write(a, v, now, 2 * cycle);
            } else {
                vb_xfer one{a, 4};
                model_->write(&one, 1, data + off);
            }
        } else if (flash_reg(a)) {
            uint32_t v = port_->read(a, now);
            const uint8_t *b = reinterpret_cast<const uint8_t *>(&v);
            out.insert(out.end(), b, b + 4);
        } else {
            vb_xfer one{a, 4};
            int rc = model_->read(&one, 1, out, err);
            if (rc < 0)
                return rc;
        }
        model_->run_until(model_->now_ns() + cycle);
        uint32_t boot = 0;
        if (port_->take_iprog(boot)) {
            // The FPGA reconfigures: the rest of the burst goes nowhere.
            boot_from_flash(boot, true);
            return 0;
        }
    }
    return 0;
}

int LocalBusBoard::lb_read(const vb_xfer *x, size_t n, std::vector<uint8_t> &out,
                           std::string &err)
{
    if (!model_) {
        err = "board " + board_ + " is not configured (blank FPGA): no local-bus target";
        return -ENODEV;
    }
    if (!port_)
        return model_->read(x, n, out, err);
    size_t i = 0;
    while (i < n) {
        if (!model_) {
            out.resize(out.size() + x[i].size, 0xFF);
            i++;
            continue;
        }
        bool flash = flash_reg(x[i].addr) ||
                     (x[i].addr < kFlashRegCtrl && x[i].addr + x[i].size > kFlashRegCtrl);
        if (flash) {
            int rc = flash_access(x[i], false, nullptr, out, err);
            if (rc < 0)
                return rc;
            i++;
            continue;
        }
        size_t j = i; // a run of xfers that do not touch the flash port
        while (j < n && !flash_reg(x[j].addr) &&
               !(x[j].addr < kFlashRegCtrl && x[j].addr + x[j].size > kFlashRegCtrl))
            j++;
        int rc = model_->read(x + i, j - i, out, err);
        if (rc < 0)
            return rc;
        i = j;
    }
    return 0;
}

int LocalBusBoard::lb_write(const vb_xfer *x, size_t n, const uint8_t *data, std::string &err)
{
    if (!model_) {
        err = "board " + board_ + " is not configured (blank FPGA): no local-bus target";
        return -ENODEV;
    }
    if (!port_) {
        model_->write(x, n, data);
        return 0;
    }
    std::vector<uint8_t> none;
    for (size_t i = 0; i < n && model_; i++) {
        bool flash = flash_reg(x[i].addr) ||
                     (x[i].addr < kFlashRegCtrl && x[i].addr + x[i].size > kFlashRegCtrl);
        if (flash) {
            int rc = flash_access(x[i], true, data, none, err);
            if (rc < 0)
                return rc;
        } else {
            model_->write(x + i, 1, data);
        }
        data += x[i].size;
    }
    return 0;
}

bool LocalBusBoard::flash_configured() const
{
    // Spartan-6 boards (5i25, 6i25, ...) configure from an SPI flash.
    return part_.compare(0, 4, "6slx") == 0;
}

int LocalBusBoard::check_image(void *ctx, const uint8_t *p, size_t n, std::string &err)
{
    const LbEntry *e = nullptr;
    return static_cast<LocalBusBoard *>(ctx)->match_image(p, n, e, err);
}

void LocalBusBoard::boot_from_flash(uint32_t addr, bool by_iprog)
{
    unconfigure();
    BootResult r = port_->boot(addr, by_iprog, check_image, this);
    if (!r.configured)
        return;
    const LbEntry *e = nullptr;
    std::string err;
    bool fast = false;
    if (match_image(r.image.data(), r.image.size(), e, err) == 0) {
        if (use_fast(*e, fast, err) < 0)
            std::fprintf(stderr, "vboard: boot from flash: %s; board stays blank\n", err.c_str());
        else
            start(*e, fast);
    }
    port_->set_bootsts(r.bootsts);
}

namespace {
// A vboard firmware image (fwimage.h) for a built firmware.
std::vector<uint8_t> make_image(const FwInfo &fw)
{
    std::vector<uint8_t> v(kFwImageSize, 0);
    auto put = [&v](size_t off, uint32_t x) {
        for (int i = 0; i < 4; i++)
            v[off + static_cast<size_t>(i)] = static_cast<uint8_t>(x >> (8 * i));
    };
    put(0, kFwMagic);
    put(4, kFwVersion);
    put(8, static_cast<uint32_t>(kFwImageSize));
    put(12, fw.idrom_crc);
    std::memcpy(v.data() + 16, fw.board, std::min<size_t>(15, std::strlen(fw.board)));
    std::memcpy(v.data() + 32, fw.firmware, std::min<size_t>(31, std::strlen(fw.firmware)));
    put(64, crc32(v.data(), 64));
    return v;
}
} // namespace

int LocalBusBoard::jtag(uint32_t levels, uint32_t &tdo, std::string &err)
{
    if (!tap_) {
        uint32_t id = xilinx_idcode(part_);
        if (!id) {
            err = "board " + board_ + " (" + part_ + ") has no JTAG port model";
            return -ENOTSUP;
        }
        tap_ = std::make_unique<JtagTap>(
            id,
            [this](const std::vector<uint8_t> &bits) {
                const LbEntry *e = nullptr;
                std::string why;
                if (match_image(bits.data(), bits.size(), e, why) < 0) {
                    std::fprintf(stderr, "vboard: %s: JTAG configuration failed, board stays "
                                         "blank: %s\n", board_.c_str(), why.c_str());
                    return -EINVAL;
                }
                bool fast = false;
                if (use_fast(*e, fast, why) < 0) {
                    std::fprintf(stderr, "vboard: %s: JTAG configuration refused, board "
                                         "stays blank: %s\n", board_.c_str(), why.c_str());
                    return -ENOTSUP;
                }
                start(*e, fast);
                return 0;
            },
            [this] { unconfigure(); }, [this] { return fw_ != nullptr; });
    }
    tdo = static_cast<uint32_t>(tap_->lines(levels));
    return 0;
}

int LocalBusBoard::attach_flash(const std::string &path, const std::string &part,
                                uint32_t speedup, const std::string &firmware, std::string &err)
{
    if (!flash_configured()) {
        err = "board " + board_ + " (" + part_ +
              ") is configured by its bus, it has no configuration flash";
        return -ENOTSUP;
    }
    const FlashPart *fp = flash_part(part.empty() ? "m25p16" : part);
    if (!fp) {
        err = "unknown flash part '" + part + "' (known: " + flash_part_names() + ")";
        return -EINVAL;
    }
    const LbEntry *fw = nullptr;
    if (!firmware.empty() && !(fw = find(firmware))) {
        err = "firmware " + firmware + " is not built into this vboard for board " + board_ +
              " (built: " + join(firmwares()) + ")";
        return -ENOENT;
    }
    auto flash = std::make_unique<SpiFlash>();
    bool created = false;
    int rc = flash->open(*fp, path, created, err);
    if (rc < 0)
        return rc;
    flash->set_speedup(speedup);
    if (created && fw) {
        std::vector<uint8_t> bb = flash_boot_block(kFlashUserAddr, kFlashFallbackAddr);
        std::vector<uint8_t> img = make_image(*fw->info);
        flash->poke(kFlashBootAddr, bb.data(), bb.size());
        flash->poke(kFlashFallbackAddr, img.data(), img.size());
        flash->poke(kFlashUserAddr, img.data(), img.size());
    }
    port_.reset();
    flash_ = std::move(flash);
    port_ = std::make_unique<FlashPort>(*flash_);
    boot_from_flash(kFlashBootAddr, false);
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
