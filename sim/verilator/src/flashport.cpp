// SPDX-License-Identifier: GPL-2.0-or-later
//
// flashport.cpp - SPI access registers, ICAP and configuration from flash
// (flashport.h).
#include "flashport.h"

#include <cerrno>
#include <cstdio>

namespace vb {

namespace {
constexpr uint16_t kSync0 = 0xAA99, kSync1 = 0x5566;
constexpr uint16_t kNoop = 0x2000;
constexpr int kRegCmd = 0x05;
constexpr int kRegGeneral1 = 0x13; // .. GENERAL4 = 0x16
constexpr uint16_t kCmdIprog = 0x000E;
constexpr size_t kMaxImage = 1u << 20; // a Spartan-6 LX9 needs 340 KB

// A type-1 packet header: 001 op(2) reg(6) count(5).
int type1_write_reg(uint16_t w, unsigned &count)
{
    if ((w >> 13) != 1 || ((w >> 11) & 3u) != 2u)
        return -1;
    count = w & 0x1Fu;
    return (w >> 5) & 0x3F;
}

void put16(std::vector<uint8_t> &v, uint16_t w)
{
    v.push_back(static_cast<uint8_t>(w >> 8));
    v.push_back(static_cast<uint8_t>(w));
}

std::string hex(uint32_t v)
{
    char b[16];
    std::snprintf(b, sizeof b, "0x%06X", v);
    return b;
}
} // namespace

std::vector<uint8_t> flash_boot_block(uint32_t user, uint32_t fallback)
{
    std::vector<uint8_t> v(10, 0xFF);
    put16(v, kSync0);
    put16(v, kSync1);
    put16(v, 0x31E1); // register 0x0F
    put16(v, 0xFFFF);
    put16(v, 0x3261); // GENERAL1: MultiBoot address 15..0
    put16(v, static_cast<uint16_t>(user));
    put16(v, 0x3281); // GENERAL2: read opcode 0x0B, address 23..16
    put16(v, static_cast<uint16_t>(0x0B00u | ((user >> 16) & 0xFFu)));
    put16(v, 0x32A1); // GENERAL3: fallback address 15..0
    put16(v, static_cast<uint16_t>(fallback));
    put16(v, 0x32C1); // GENERAL4: opcode, fallback address 23..16
    put16(v, static_cast<uint16_t>(0x0B00u | ((fallback >> 16) & 0xFFu)));
    put16(v, 0x30A1); // CMD: NULL
    put16(v, 0x0000);
    put16(v, 0x3301); // register 0x18
    put16(v, 0x2100);
    put16(v, 0x3201); // register 0x10
    put16(v, 0x001F);
    put16(v, 0x30A1); // CMD
    put16(v, kCmdIprog);
    for (int i = 0; i < 7; i++)
        put16(v, kNoop);
    return v;
}

uint32_t FlashPort::read(uint32_t addr, uint64_t now)
{
    switch (addr) {
    case kFlashRegCtrl: return (now >= dav_at_ ? 4u : 0u) | (cs_high_ ? 1u : 0u);
    case kFlashRegData: return rx_;
    case kFlashRegIcap: return kIcapCookie;
    case kFlashRegBootsts: return bootsts_;
    default: return 0;
    }
}

void FlashPort::write(uint32_t addr, uint32_t value, uint64_t now, uint64_t sck_ns)
{
    switch (addr) {
    case kFlashRegCtrl: {
        bool high = (value & 1u) != 0;
        if (high != cs_high_)
            flash_.select(!high, now);
        cs_high_ = high;
        break;
    }
    case kFlashRegData:
        rx_ = flash_.transfer(static_cast<uint8_t>(value), now);
        dav_at_ = now + 8 * sck_ns;
        break;
    case kFlashRegIcap: {
        uint16_t w = static_cast<uint16_t>(value);
        if (!synced_) {
            synced_ = (w == kSync1 && want_reg_ == -2);
            want_reg_ = w == kSync0 ? -2 : -1;
            break;
        }
        if (want_reg_ >= 0) {
            int reg = want_reg_;
            want_reg_ = -1;
            if (reg >= kRegGeneral1 && reg < kRegGeneral1 + 4)
                general_[reg - kRegGeneral1] = w;
            else if (reg == kRegCmd && w == kCmdIprog)
                iprog_ = true;
            break;
        }
        unsigned count = 0;
        int reg = type1_write_reg(w, count);
        if (reg >= 0 && count == 1)
            want_reg_ = reg;
        break;
    }
    default: break;
    }
}

bool FlashPort::take_iprog(uint32_t &addr)
{
    if (!iprog_)
        return false;
    iprog_ = false;
    synced_ = false;
    want_reg_ = -1;
    addr = static_cast<uint32_t>(general_[1] & 0xFFu) << 16 | general_[0];
    return true;
}

namespace {
// Follow a boot block at addr: true and the two addresses when it holds
// a sync word, MultiBoot/fallback addresses and IPROG.
bool parse_boot_block(const SpiFlash &f, uint32_t addr, uint32_t &user, uint32_t &fallback)
{
    const uint8_t *m = f.data();
    uint32_t size = f.part().size;
    uint32_t p = addr;
    while (p < size && p < addr + 64 && m[p] == 0xFF)
        p++;
    if (p + 4 > size || m[p] != 0xAA || m[p + 1] != 0x99 || m[p + 2] != 0x55 || m[p + 3] != 0x66)
        return false;
    p += 4;
    uint16_t g[4] = {0, 0, 0, 0};
    for (int words = 0; words < 64 && p + 4 <= size; words++) {
        uint16_t w = static_cast<uint16_t>(m[p] << 8 | m[p + 1]);
        p += 2;
        unsigned count = 0;
        int reg = type1_write_reg(w, count);
        if (reg < 0 || count != 1)
            continue;
        uint16_t v = static_cast<uint16_t>(m[p] << 8 | m[p + 1]);
        p += 2;
        if (reg >= kRegGeneral1 && reg < kRegGeneral1 + 4)
            g[reg - kRegGeneral1] = v;
        if (reg == kRegCmd && v == kCmdIprog) {
            user = static_cast<uint32_t>(g[1] & 0xFFu) << 16 | g[0];
            fallback = static_cast<uint32_t>(g[3] & 0xFFu) << 16 | g[2];
            return true;
        }
    }
    return false;
}

// The image at addr: a vboard firmware image carries its length at 8..11.
std::vector<uint8_t> image_at(const SpiFlash &f, uint32_t addr)
{
    const uint8_t *m = f.data();
    uint32_t size = f.part().size;
    if (addr >= size || size - addr < 12)
        return {};
    uint32_t len = static_cast<uint32_t>(m[addr + 8]) | static_cast<uint32_t>(m[addr + 9]) << 8 |
                   static_cast<uint32_t>(m[addr + 10]) << 16 |
                   static_cast<uint32_t>(m[addr + 11]) << 24;
    if (len < 12 || len > kMaxImage || len > size - addr)
        len = 68; // let the image check say what is wrong
    if (len > size - addr)
        return {};
    return std::vector<uint8_t>(m + addr, m + addr + len);
}
} // namespace

BootResult FlashPort::boot(uint32_t addr, bool by_iprog, ImageCheck check, void *ctx)
{
    BootResult r;
    uint32_t user = addr, fallback = 0;
    bool have_fallback = false;
    if (parse_boot_block(flash_, addr, user, fallback)) {
        have_fallback = true;
        r.log = "boot block at " + hex(addr) + ": MultiBoot " + hex(user) + ", fallback " +
                hex(fallback);
    }
    uint32_t sts = by_iprog ? BOOTSTS_IPROG : 0u;
    auto attempt = [&](uint32_t a, const char *what) {
        std::vector<uint8_t> img = image_at(flash_, a);
        std::string err = "no image";
        int rc = img.empty() ? -EINVAL : check(ctx, img.data(), img.size(), err);
        r.log += std::string(r.log.empty() ? "" : "; ") + what + " image at " + hex(a) + ": " +
                 (rc == 0 ? "configured" : err);
        if (rc == 0) {
            r.configured = true;
            r.from = a;
            r.image = std::move(img);
            return true;
        }
        sts |= rc == -ENODEV ? BOOTSTS_ID_ERROR : BOOTSTS_CRC_ERROR;
        return false;
    };
    if (attempt(user, have_fallback ? "MultiBoot" : "configuration")) {
        sts |= BOOTSTS_VALID;
    } else if (have_fallback && attempt(fallback, "fallback")) {
        sts |= BOOTSTS_VALID | BOOTSTS_FALLBACK;
    }
    r.bootsts = sts;
    bootsts_ = sts;
    return r;
}

} // namespace vb
