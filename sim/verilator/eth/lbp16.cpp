// SPDX-License-Identifier: GPL-2.0-or-later
//
// lbp16.cpp - the LBP16 command engine (lbp16.h, spec/hostmot2.md 17.3).
#include "lbp16.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace vb::eth {

namespace {
constexpr size_t kMaxReply = 65507; // what one UDP datagram can carry

struct SpaceInfo {
    const char *name;   // 8 characters, NUL padded
    uint16_t type_size; // info word 1
    uint16_t range;     // info word 2
    uint32_t bytes;     // what the engine accepts
    unsigned size_mask; // allowed element sizes, bit k = 2^k bytes
};

const SpaceInfo kSpaces[8] = {
    {"HostMot2", 0x8104, 16, 0x10000, 1u << 2},
    {"KSZ8851", 0x8102, 8, 0x100, 1u << 1},
    {"EtherEEP", 0x8E02, 7, 0x80, 1u << 1},
    {"FPGAFlsh", 0x8F04, 0x8200, 0x10, 1u << 2},
    {"Timers", 0x8202, 4, 0x20, 1u << 1},
    {nullptr, 0, 0, 0, 0},
    {"LBP16RW", 0x8202, 4, 0x20, 1u << 1},
    {"LBP16RO", 0x0202, 4, 0x20, 1u << 1},
};

uint16_t le16(const uint8_t *p) { return static_cast<uint16_t>(p[0] | p[1] << 8); }
uint32_t le32(const uint8_t *p)
{
    return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
           static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}
void put16(std::vector<uint8_t> &v, uint16_t x)
{
    v.push_back(static_cast<uint8_t>(x));
    v.push_back(static_cast<uint8_t>(x >> 8));
}
void put32(std::vector<uint8_t> &v, uint32_t x)
{
    put16(v, static_cast<uint16_t>(x));
    put16(v, static_cast<uint16_t>(x >> 16));
}
} // namespace

uint32_t lbp16_space_range(unsigned space) { return space < 8 ? kSpaces[space].bytes : 0; }

Lbp16::Lbp16(Lbp16Target &t, const Lbp16Identity &id)
    : t_(t), id_(id), eth_chip_(0x80), eeprom_(0x40), timers_(0x10), status_(0x10), info_(0x10)
{
    // EEPROM: MAC low/mid/high words at 2/4/6, board name at 0x10, IP at 0x20.
    const auto &m = id_.mac;
    eeprom_[1] = static_cast<uint16_t>(m[4] << 8 | m[5]);
    eeprom_[2] = static_cast<uint16_t>(m[2] << 8 | m[3]);
    eeprom_[3] = static_cast<uint16_t>(m[0] << 8 | m[1]);
    char name[16] = {};
    std::memcpy(name, id_.board_name.data(), std::min(id_.board_name.size(), sizeof name));
    for (unsigned i = 0; i < 8; i++) {
        uint16_t w = static_cast<uint16_t>(static_cast<uint8_t>(name[2 * i]) |
                                           static_cast<uint8_t>(name[2 * i + 1]) << 8);
        eeprom_[8 + i] = w;
        info_[i] = w;
    }
    eeprom_[0x10] = static_cast<uint16_t>(id_.ip);
    eeprom_[0x11] = static_cast<uint16_t>(id_.ip >> 16);
    info_[8] = 3; // LBP16 version
    info_[9] = id_.fw_version;
    info_[10] = id_.ip_source;
}

std::vector<uint16_t> *Lbp16::mem(unsigned space)
{
    switch (space) {
    case kSpaceEthChip: return &eth_chip_;
    case kSpaceEeprom: return &eeprom_;
    case kSpaceTimers: return &timers_;
    case kSpaceStatus: return &status_;
    case kSpaceInfo: return &info_;
    default: return nullptr;
    }
}

const std::vector<uint16_t> *Lbp16::mem(unsigned space) const
{
    return const_cast<Lbp16 *>(this)->mem(space);
}

uint16_t Lbp16::word(unsigned space, unsigned addr) const
{
    const std::vector<uint16_t> *m = mem(space);
    if (!m || addr / 2 >= m->size())
        return 0;
    if (space == kSpaceTimers && addr == 0)
        return static_cast<uint16_t>(t_.now_us());
    return (*m)[addr / 2];
}

void Lbp16::bump(unsigned reg)
{
    uint16_t &w = status_[reg / 2];
    w = static_cast<uint16_t>(w + 1);
}

void Lbp16::count_tx(bool ok)
{
    bump(ok ? kStTxPackets : kStTxBad);
    if (ok)
        bump(kStTxUdp);
}

void Lbp16::fail(Fail f, const std::string &why)
{
    switch (f) {
    case Fail::kParse:
        status_[kStErrorFlags / 2] |= 1;
        bump(kStParseErrors);
        break;
    case Fail::kMemory:
        status_[kStErrorFlags / 2] |= 2;
        bump(kStMemErrors);
        break;
    case Fail::kWrite:
        status_[kStErrorFlags / 2] |= 4;
        bump(kStWriteErrors);
        break;
    case Fail::kNone: break;
    }
    last_error_ = why;
}

bool Lbp16::handle(const uint8_t *pkt, size_t n, std::vector<uint8_t> &reply)
{
    bool send = run_datagram(pkt, n, reply);
    if (!send)
        reply.clear(); // never a partial reply of a refused datagram
    return send;
}

bool Lbp16::run_datagram(const uint8_t *pkt, size_t n, std::vector<uint8_t> &reply)
{
    reply.clear();
    last_error_.clear();
    bump(kStRxPackets);
    bump(kStRxUdp);
    write_enabled_ = false;
    size_t off = 0;
    bool any_read = false;
    char why[160];
    if (n < 2) {
        bump(kStRxBad);
        fail(Fail::kParse, "datagram of " + std::to_string(n) + " bytes holds no command");
        return false;
    }
    while (off < n) {
        if (n - off < 2) {
            std::snprintf(why, sizeof why, "command at byte %zu: datagram ends inside it", off);
            fail(Fail::kParse, why);
            return false;
        }
        uint16_t w = le16(pkt + off);
        Cmd c{(w & 0x8000) != 0, (w & 0x4000) != 0, (w & 0x2000) != 0, (w & 0x80) != 0,
              (w >> 10) & 7u,    1u << ((w >> 8) & 3), w & 0x7Fu};
        size_t at = off;
        off += 2;
        if (c.count == 0) {
            std::snprintf(why, sizeof why, "command 0x%04x at byte %zu: element count 0", w, at);
            fail(Fail::kParse, why);
            return false;
        }
        uint32_t addr = ptr_[c.space];
        if (c.has_addr) {
            if (n - off < 2) {
                std::snprintf(why, sizeof why, "command 0x%04x at byte %zu: address missing", w,
                              at);
                fail(Fail::kParse, why);
                return false;
            }
            addr = le16(pkt + off);
            off += 2;
        }
        size_t dlen = static_cast<size_t>(c.count) * c.size;
        if (c.write && n - off < dlen) {
            std::snprintf(why, sizeof why,
                          "write command 0x%04x at byte %zu: %zu data bytes, datagram has %zu", w,
                          at, dlen, n - off);
            fail(Fail::kParse, why);
            return false;
        }
        if (!c.write && reply.size() + dlen > kMaxReply) {
            fail(Fail::kMemory, "reply would not fit in one datagram");
            return false;
        }
        Fail f = run(c, addr, c.write ? pkt + off : nullptr, reply);
        if (f != Fail::kNone) {
            std::snprintf(why, sizeof why,
                          "command 0x%04x at byte %zu (%s %u x %u bytes, space %u%s, address "
                          "0x%04x): %s",
                          w, at, c.write ? "write" : "read", c.count, c.size, c.space,
                          c.info ? " info area" : "", addr,
                          f == Fail::kWrite ? "write refused" : "no such memory or element size");
            fail(f, why);
            return false;
        }
        if (c.write)
            off += dlen;
        else
            any_read = true;
        if (!c.info)
            ptr_[c.space] = addr + (c.inc ? static_cast<uint32_t>(dlen) : 0);
    }
    write_enabled_ = false;
    return any_read;
}

Lbp16::Fail Lbp16::run(const Cmd &c, uint32_t addr, const uint8_t *data,
                       std::vector<uint8_t> &reply)
{
    const SpaceInfo &s = kSpaces[c.space];
    if (c.info) {
        if (c.write)
            return Fail::kWrite;
        return info_read(c, addr, reply);
    }
    if (!s.name || !(s.size_mask & c.size))
        return Fail::kMemory;
    uint32_t span = c.inc ? c.count * c.size : c.size;
    if (addr % c.size || addr >= s.bytes || span > s.bytes - addr)
        return Fail::kMemory;
    switch (c.space) {
    case kSpaceHm2:
        if (c.write)
            return t_.hm2_write(addr, c.count, c.inc, data) ? Fail::kNone : Fail::kMemory;
        {
            size_t at = reply.size();
            reply.resize(at + c.count * 4u);
            return t_.hm2_read(addr, c.count, c.inc, reply.data() + at) ? Fail::kNone
                                                                         : Fail::kMemory;
        }
    case kSpaceFlash: return flash(c, addr, data, reply);
    default: return c.write ? small_write(c, addr, data) : small_read(c, addr, reply);
    }
}

Lbp16::Fail Lbp16::small_read(const Cmd &c, uint32_t addr, std::vector<uint8_t> &reply)
{
    for (unsigned i = 0; i < c.count; i++) {
        put16(reply, word(c.space, addr));
        if (c.inc)
            addr += 2;
    }
    return Fail::kNone;
}

bool Lbp16::store_word(unsigned space, uint32_t addr, uint16_t v)
{
    switch (space) {
    case kSpaceInfo: return false;
    case kSpaceEeprom:
        if (!write_enabled_)
            return false;
        break;
    case kSpaceTimers:
        if (addr == 0x02)
            t_.wait_us(v);
        break;
    case kSpaceStatus:
        if (addr == kStWriteEnable)
            write_enabled_ = v == kWriteEnableKey;
        else if (addr == kStReset && v != 0)
            t_.reset();
        else if (addr == kStReconfig)
            t_.icap_word(v);
        break;
    default: break;
    }
    (*mem(space))[addr / 2] = v;
    return true;
}

Lbp16::Fail Lbp16::small_write(const Cmd &c, uint32_t addr, const uint8_t *data)
{
    for (unsigned i = 0; i < c.count; i++) {
        if (!store_word(c.space, addr, le16(data + 2 * i)))
            return Fail::kWrite;
        if (c.inc)
            addr += 2;
    }
    return Fail::kNone;
}

Lbp16::Fail Lbp16::info_read(const Cmd &c, uint32_t addr, std::vector<uint8_t> &reply)
{
    const SpaceInfo &s = kSpaces[c.space];
    uint32_t span = c.inc ? c.count * 2u : 2u;
    if (!s.name || c.size != 2 || addr % 2 || addr >= 16 || span > 16 - addr)
        return Fail::kMemory;
    char name[8] = {};
    std::memcpy(name, s.name, std::strlen(s.name));
    for (unsigned i = 0; i < c.count; i++) {
        unsigned k = addr / 2;
        uint16_t v = 0;
        switch (k) {
        case 0: v = static_cast<uint16_t>(0x5A00 + c.space); break;
        case 1: v = s.type_size; break;
        case 2: v = s.range; break;
        case 3: v = static_cast<uint16_t>(ptr_[c.space]); break;
        default:
            v = static_cast<uint16_t>(static_cast<uint8_t>(name[2 * (k - 4)]) |
                                      static_cast<uint8_t>(name[2 * (k - 4) + 1]) << 8);
        }
        put16(reply, v);
        if (c.inc)
            addr += 2;
    }
    return Fail::kNone;
}

Lbp16::Fail Lbp16::flash(const Cmd &c, uint32_t addr, const uint8_t *data,
                         std::vector<uint8_t> &reply)
{
    for (unsigned i = 0; i < c.count; i++) {
        if (c.write) {
            if (!t_.flash_write(addr, le32(data + 4 * i), write_enabled_))
                return Fail::kWrite;
        } else {
            uint32_t v = 0;
            if (!t_.flash_read(addr, v))
                return Fail::kMemory;
            put32(reply, v);
        }
        if (c.inc)
            addr += 4;
    }
    return Fail::kNone;
}

} // namespace vb::eth
