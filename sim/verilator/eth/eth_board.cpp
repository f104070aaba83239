// SPDX-License-Identifier: GPL-2.0-or-later
//
// eth_board.cpp - Mesa Ethernet boards in the virtual board (eth_board.h).
#include "eth_board.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "fwimage.h"

namespace vb::eth {

namespace {

struct EthModel {
    const char *board;      // vboard name
    const char *lbp16_name; // LBP16 board name (space 7)
    FlashLayout flash;
};

// Where mesaflash writes the configurations (tests/data/eth/mesaflash):
// 7i92, Spartan-6 with a 16 Mbit SPI flash: boot block at 0, fallback at
// 64 KiB, user configuration at 1 MiB; 7I96S, Efinix T20 with a 32 Mbit
// flash: fallback at 0, user configuration at 2 MiB.  64 KiB sectors.
const EthModel kModels[] = {
    {"7i92", "7I92", {2u << 20, 0x14, 0x100000, 0x10000, 0x10000}},
    // 7I76E: Spartan-6 LX16, 16 Mbit flash laid out like the 7i92's
    // (assumed: mesaflash's 7I76E figures are not recorded here).
    {"7i76e", "7I76E-16", {2u << 20, 0x14, 0x100000, 0x10000, 0x10000}},
    {"7i96s", "7I96S", {4u << 20, 0x15, 0x200000, 0x0, 0x10000}},
};

// The Spartan-6 boot block as mesaflash --fix-boot-block writes it to a
// 7i92 (spec/hostmot2.md 17.3, recorded in tests/data/eth/mesaflash):
// dummy words, sync, GENERAL1/2 = MultiBoot (user) address with read
// opcode 0x0B, GENERAL3/4 = fallback address, then IPROG and seven
// NOOPs, in a 256-byte page padded with zeros.
std::vector<uint8_t> mesa_boot_block(uint32_t user, uint32_t fallback)
{
    const uint16_t words[] = {
        0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xFFFF, 0xAA99, 0x5566, 0x31E1, 0xFFFF, 0x3261,
        static_cast<uint16_t>(user), 0x3281, static_cast<uint16_t>(0x0B00 | (user >> 16 & 0xFF)),
        0x32A1, static_cast<uint16_t>(fallback), 0x32C1,
        static_cast<uint16_t>(0x0B00 | (fallback >> 16 & 0xFF)), 0x30A1, 0x0000, 0x3301, 0x2100,
        0x3201, 0x001F, 0x30A1, 0x000E, 0x2000, 0x2000, 0x2000, 0x2000, 0x2000, 0x2000, 0x2000};
    std::vector<uint8_t> v;
    for (uint16_t w : words) { // big-endian, as the configuration logic reads the flash
        v.push_back(static_cast<uint8_t>(w >> 8));
        v.push_back(static_cast<uint8_t>(w));
    }
    v.resize(256, 0x00); // one flash page, the rest zero
    return v;
}

const EthModel *model_of(const std::string &board)
{
    for (const EthModel &m : kModels)
        if (board == m.board)
            return &m;
    return nullptr;
}

const uint8_t kBitHeader[13] = {0x00, 0x09, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F,
                                0xF0, 0x0F, 0xF0, 0x00, 0x00, 0x01};

void small_chunk(std::vector<uint8_t> &v, char tag, const std::string &text)
{
    size_t len = text.size() + 1;
    v.push_back(static_cast<uint8_t>(tag));
    v.push_back(static_cast<uint8_t>(len >> 8));
    v.push_back(static_cast<uint8_t>(len));
    v.insert(v.end(), text.begin(), text.end());
    v.push_back(0);
}

void put_le32(std::vector<uint8_t> &v, uint32_t x)
{
    for (int i = 0; i < 4; i++)
        v.push_back(static_cast<uint8_t>(x >> (8 * i)));
}

// The 'e' payload of a .BIT at `p` (n bytes available); false if `p` does
// not start a well-formed .BIT container.
bool bit_payload(const uint8_t *p, size_t n, const uint8_t *&e, size_t &elen)
{
    if (n < sizeof kBitHeader || std::memcmp(p, kBitHeader, sizeof kBitHeader) != 0)
        return false;
    size_t off = sizeof kBitHeader;
    while (off < n) {
        char tag = static_cast<char>(p[off++]);
        if (tag == 'e') {
            if (n - off < 4)
                return false;
            size_t len = static_cast<size_t>(p[off]) << 24 | static_cast<size_t>(p[off + 1]) << 16 |
                         static_cast<size_t>(p[off + 2]) << 8 | p[off + 3];
            off += 4;
            if (len > n - off)
                return false;
            e = p + off;
            elen = len;
            return true;
        }
        if (tag < 'a' || tag > 'd' || n - off < 2)
            return false;
        size_t len = static_cast<size_t>(p[off]) << 8 | p[off + 1];
        off += 2 + len;
    }
    return false;
}

} // namespace

std::vector<uint8_t> builtin_bitfile(const std::string &board, const std::string &firmware,
                                     const std::string &part, uint32_t idrom_crc)
{
    std::vector<uint8_t> img;
    put_le32(img, kFwMagic);
    put_le32(img, kFwVersion);
    put_le32(img, static_cast<uint32_t>(kFwImageSize));
    put_le32(img, idrom_crc);
    char b[16] = {}, f[32] = {};
    std::strncpy(b, board.c_str(), sizeof b - 1);
    std::strncpy(f, firmware.c_str(), sizeof f - 1);
    img.insert(img.end(), b, b + sizeof b);
    img.insert(img.end(), f, f + sizeof f);
    put_le32(img, crc32(img.data(), img.size()));

    std::vector<uint8_t> v(kBitHeader, kBitHeader + sizeof kBitHeader);
    small_chunk(v, 'a', firmware + ".ncd;UserID=0xFFFFFFFF");
    small_chunk(v, 'b', part);
    small_chunk(v, 'c', "2026/01/01");
    small_chunk(v, 'd', "00:00:00");
    v.push_back('e');
    uint32_t n = static_cast<uint32_t>(img.size());
    for (int i = 3; i >= 0; i--)
        v.push_back(static_cast<uint8_t>(n >> (8 * i)));
    v.insert(v.end(), img.begin(), img.end());
    return v;
}

// The engine's view of the board.
class EthBoard::Target final : public Lbp16Target {
  public:
    explicit Target(EthBoard &b) : b_(b) {}

    bool hm2_read(uint32_t addr, unsigned count, bool inc, uint8_t *out) override
    {
        std::vector<vb_xfer> x;
        if (inc)
            x.push_back({addr, count * 4u});
        else
            x.assign(count, vb_xfer{addr, 4});
        std::vector<uint8_t> data;
        std::string err;
        if (b_.lb_.lb_read(x.data(), x.size(), data, err) < 0 || data.size() != count * 4u)
            return false;
        std::memcpy(out, data.data(), data.size());
        return true;
    }
    bool hm2_write(uint32_t addr, unsigned count, bool inc, const uint8_t *data) override
    {
        std::vector<vb_xfer> x;
        if (inc)
            x.push_back({addr, count * 4u});
        else
            x.assign(count, vb_xfer{addr, 4});
        std::string err;
        return b_.lb_.lb_write(x.data(), x.size(), data, err) == 0;
    }
    bool flash_read(uint32_t reg, uint32_t &v) override
    {
        switch (reg) {
        case 0x0: v = b_.flash_addr_; return true;
        case 0x4: {
            uint32_t a = b_.flash_addr_ & (b_.layout_.size - 1) & ~3u;
            std::memcpy(&v, &b_.flash_[a], 4);
            b_.flash_addr_ = (a + 4) & (b_.layout_.size - 1);
            return true;
        }
        case 0x8: v = b_.layout_.id; return true;
        default: return false; // 0xC (erase) is write-only
        }
    }
    bool flash_write(uint32_t reg, uint32_t v, bool enabled) override
    {
        switch (reg) {
        case 0x0: b_.flash_addr_ = v & (b_.layout_.size - 1); return true;
        case 0x4: {
            if (!enabled)
                return false;
            uint32_t a = b_.flash_addr_ & (b_.layout_.size - 1) & ~3u;
            for (int i = 0; i < 4; i++) // programming only clears bits
                b_.flash_[a + i] &= static_cast<uint8_t>(v >> (8 * i));
            b_.flash_addr_ = (a + 4) & (b_.layout_.size - 1);
            b_.flash_dirty_ = true;
            return true;
        }
        case 0xC: {
            if (!enabled)
                return false;
            uint32_t a = b_.flash_addr_ & (b_.layout_.size - 1) & ~(b_.layout_.erase_size - 1);
            std::fill(b_.flash_.begin() + a, b_.flash_.begin() + a + b_.layout_.erase_size,
                      0xFF);
            b_.flash_dirty_ = true;
            return true;
        }
        default: return false;
        }
    }
    uint64_t now_us() const override { return b_.now_ns() / 1000; }
    void wait_us(unsigned us) override { b_.run_until(b_.now_ns() + us * 1000ull); }
    void reset() override { b_.reset_pending_ = true; }
    void icap_word(uint16_t w) override
    {
        b_.icap_.push_back(w);
        size_t n = b_.icap_.size();
        // Spartan-6 (7i92): IPROG, a command-register write (0x30A1) of
        // 0x000E.  Efinix (7i96S): mesaflash --reload writes 0x0005 then
        // 0x000D.  The FPGA reconfigures after the datagram.
        if (n >= 2 && ((b_.icap_[n - 2] == 0x30A1 && b_.icap_[n - 1] == 0x000E) ||
                       (b_.icap_[n - 2] == 0x0005 && b_.icap_[n - 1] == 0x000D)))
            b_.reload_pending_ = true;
        if (n > 64)
            b_.icap_.erase(b_.icap_.begin(), b_.icap_.begin() + 32);
    }

  private:
    EthBoard &b_;
};

EthBoard::EthBoard(const std::string &board) : lb_(board), target_(new Target(*this))
{
    const EthModel *m = model_of(board);
    lbp16_name_ = m->lbp16_name;
    layout_ = m->flash;
    flash_.assign(layout_.size, 0xFF);
    set_ip(0x7F000001);
}

EthBoard::~EthBoard() { save_flash(); }

void EthBoard::set_ip(uint32_t ip)
{
    ip_ = ip;
    Lbp16Identity id;
    id.board_name = lbp16_name_;
    id.mac = {0x00, 0x60, 0x1B, static_cast<uint8_t>(ip >> 16), static_cast<uint8_t>(ip >> 8),
              static_cast<uint8_t>(ip)};
    id.ip = ip;
    engine_ = std::make_unique<Lbp16>(*target_, id);
}

int EthBoard::attach_flash_file(const std::string &path, bool &fresh, std::string &err)
{
    std::ifstream in(path, std::ios::binary);
    fresh = !in;
    if (in) {
        std::vector<uint8_t> v((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
        if (v.size() != flash_.size()) {
            err = "flash image " + path + " has " + std::to_string(v.size()) +
                  " bytes; the " + name() + "'s flash has " + std::to_string(flash_.size());
            return -EINVAL;
        }
        flash_ = std::move(v);
    }
    flash_path_ = path;
    flash_dirty_ = true;
    save_flash();
    if (flash_dirty_) {
        err = "cannot write flash image " + path + ": " + std::strerror(errno);
        flash_path_.clear();
        return -EIO;
    }
    return 0;
}

int EthBoard::attach_flash(const std::string &path, const std::string &part, uint32_t speedup,
                           const std::string &firmware, std::string &err)
{
    (void)speedup; // programming and erasing take no board time here
    if (!part.empty()) {
        err = "the " + name() + "'s flash is fixed (--flash-part is for the SPI-flash boards)";
        return -EINVAL;
    }
    bool fresh = true;
    if (!path.empty()) {
        int r = attach_flash_file(path, fresh, err);
        if (r < 0)
            return r;
    }
    if (fresh && !firmware.empty()) {
        int r = program_builtin(firmware, err);
        if (r < 0)
            return r;
    }
    boot_from_flash();
    return 0;
}

int EthBoard::program_builtin(const std::string &firmware, std::string &err)
{
    for (size_t i = 0; i < kNumLbModels; i++) {
        const FwInfo &fi = *kLbModels[i].info;
        if (name() != fi.board || firmware != fi.firmware)
            continue;
        std::vector<uint8_t> bit = builtin_bitfile(fi.board, fi.firmware, fi.fpga_part,
                                                   fi.idrom_crc);
        for (uint32_t a : {layout_.fallback_addr, layout_.user_addr}) {
            std::fill(flash_.begin() + a, flash_.begin() + a + layout_.erase_size, 0xFF);
            std::copy(bit.begin(), bit.end(), flash_.begin() + a);
        }
        if (layout_.fallback_addr != 0) { // Spartan-6: the boot block at 0 (mesaflash checks it)
            std::vector<uint8_t> bb = mesa_boot_block(layout_.user_addr, layout_.fallback_addr);
            std::fill(flash_.begin(), flash_.begin() + layout_.erase_size, 0xFF);
            std::copy(bb.begin(), bb.end(), flash_.begin());
        }
        flash_dirty_ = true;
        save_flash();
        return 0;
    }
    std::string known;
    for (const std::string &f : firmwares())
        known += (known.empty() ? "" : ", ") + f;
    err = "firmware " + firmware + " is not built into this vboard for board " + name() +
          " (built: " + known + ")";
    return -ENOENT;
}

void EthBoard::save_flash()
{
    if (!flash_dirty_ || flash_path_.empty())
        return;
    std::string tmp = flash_path_ + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char *>(flash_.data()),
                  static_cast<std::streamsize>(flash_.size()));
        if (!out)
            return;
    }
    if (std::rename(tmp.c_str(), flash_path_.c_str()) == 0)
        flash_dirty_ = false;
}

bool EthBoard::configure_from(uint32_t addr, std::string &why)
{
    const uint8_t *p = flash_.data() + addr;
    size_t n = flash_.size() - addr;
    const uint8_t *e = p;
    size_t elen = std::min<size_t>(n, kFwImageSize);
    if (!bit_payload(p, n, e, elen) && !(n >= 4 && std::memcmp(p, "VBFW", 4) == 0)) {
        char b[80];
        std::snprintf(b, sizeof b, "no firmware at flash address 0x%06x", addr);
        why = b;
        return false;
    }
    vb_config_status st;
    return lb_.config(VB_CONFIG_PROGRAM, e, elen, st, why) == 0;
}

void EthBoard::boot_from_flash()
{
    std::string why, why2;
    if (configure_from(layout_.user_addr, why) || configure_from(layout_.fallback_addr, why2))
        return;
    std::fprintf(stderr, "vboard: %s: %s; %s; the FPGA stays blank\n", name().c_str(),
                 why.c_str(), why2.c_str());
}

void EthBoard::reload()
{
    vb_config_status st;
    std::string err;
    lb_.config(VB_CONFIG_RESET, nullptr, 0, st, err);
    boot_from_flash();
    set_ip(ip_); // the Ethernet engine restarts too: counters and pointers cleared
}

bool EthBoard::lbp16(const uint8_t *pkt, size_t n, std::vector<uint8_t> &reply)
{
    bool r = engine_->handle(pkt, n, reply);
    if (reset_pending_) {
        reset_pending_ = false;
        std::string fw = lb_.firmware(), err;
        if (!fw.empty())
            lb_.load(fw, err);
    }
    if (reload_pending_) {
        reload_pending_ = false;
        icap_.clear();
        save_flash();
        reload();
        return false; // the FPGA reconfigures: this datagram's reply is lost
    }
    save_flash();
    return r;
}

int EthBoard::config(uint32_t op, const uint8_t *bits, size_t len, vb_config_status &st,
                     std::string &err)
{
    if (op == VB_CONFIG_PROGRAM) {
        err = "board " + name() +
              " is configured from its flash: write the firmware with hm2flash or mesaflash "
              "(LBP16 space 3) and reload";
        lb_.config(VB_CONFIG_STATUS, nullptr, 0, st, err);
        return -ENOTSUP;
    }
    return lb_.config(op, bits, len, st, err);
}

int EthBoard::load(const std::string &firmware, std::string &err)
{
    int r = program_builtin(firmware, err);
    if (r < 0)
        return r;
    std::string why;
    if (!configure_from(layout_.user_addr, why)) {
        err = why;
        return -EIO;
    }
    return 0;
}

std::vector<std::string> eth_boards()
{
    std::vector<std::string> v;
    for (const std::string &b : localbus_boards())
        if (model_of(b))
            v.push_back(b);
    return v;
}

std::unique_ptr<Board> make_eth_board(const std::string &board)
{
    std::vector<std::string> known = eth_boards();
    if (std::find(known.begin(), known.end(), board) == known.end())
        return nullptr;
    return std::make_unique<EthBoard>(board);
}

} // namespace vb::eth

extern const vb::BoardFactory vb_factory_eth;
const vb::BoardFactory vb_factory_eth = {vb::eth::eth_boards, vb::eth::make_eth_board};
