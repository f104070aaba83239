// SPDX-License-Identifier: GPL-2.0-or-later
//
// test_lbp16_responder.cpp - the virtual board's LBP16 command engine
// (sim/verilator/eth/lbp16.cpp) behind a recording fake board, checked
// against spec/hostmot2.md 17.3: every space and its info area, element
// sizes, address increment and the per-space address pointer, the write
// enable key, and every malformed datagram refused (no reply, the error
// counted in space 6, a reason naming the command).  Requests come from the
// host side's builder (lbp16.c), so the two sides are checked together.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "check.h"
#include "host/driver/backends/eth/lbp16.h" // host side (C)
#include "sim/verilator/eth/lbp16.h"        // the engine

namespace {

using vb::eth::Lbp16;
using vb::eth::Lbp16Identity;
using vb::eth::Lbp16Target;

class FakeBoard final : public Lbp16Target {
  public:
    uint8_t hm2[0x10000] = {};
    uint32_t flash_regs[4] = {0, 0, 0x16, 0};
    unsigned hm2_reads = 0, hm2_writes = 0, resets = 0, waited_us = 0;
    bool last_inc = false;
    std::vector<uint16_t> icap;
    std::vector<uint32_t> flash_writes;

    bool hm2_read(uint32_t addr, unsigned count, bool inc, uint8_t *out) override
    {
        hm2_reads++;
        last_inc = inc;
        for (unsigned i = 0; i < count; i++) {
            uint32_t a = inc ? addr + 4 * i : addr;
            if (a + 4 > sizeof hm2)
                return false;
            std::memcpy(out + 4 * i, hm2 + a, 4);
        }
        return true;
    }
    bool hm2_write(uint32_t addr, unsigned count, bool inc, const uint8_t *data) override
    {
        hm2_writes++;
        last_inc = inc;
        for (unsigned i = 0; i < count; i++) {
            uint32_t a = inc ? addr + 4 * i : addr;
            if (a + 4 > sizeof hm2)
                return false;
            std::memcpy(hm2 + a, data + 4 * i, 4);
        }
        return true;
    }
    bool flash_read(uint32_t reg, uint32_t &v) override
    {
        if (reg > 8)
            return false;
        v = flash_regs[reg / 4];
        return true;
    }
    bool flash_write(uint32_t reg, uint32_t v, bool enabled) override
    {
        if (reg == 8 || (reg != 0 && !enabled))
            return false;
        flash_regs[reg / 4] = v;
        flash_writes.push_back(v);
        return true;
    }
    uint64_t now_us() const override { return 0x12345678ABCDull; }
    void wait_us(unsigned us) override { waited_us += us; }
    void reset() override { resets++; }
    void icap_word(uint16_t w) override { icap.push_back(w); }
};

struct Rig {
    FakeBoard board;
    Lbp16 engine;
    std::vector<uint8_t> reply;
    explicit Rig(const Lbp16Identity &id) : engine(board, id) {}
    bool send(const std::vector<uint8_t> &d) { return engine.handle(d.data(), d.size(), reply); }
    bool send(const lbp16_pkt &p) { return engine.handle(p.buf, p.len, reply); }
    uint16_t st(unsigned reg) const { return engine.word(vb::eth::kSpaceStatus, reg); }
    unsigned r16(size_t i) const { return reply[2 * i] | reply[2 * i + 1] << 8; }
    uint32_t r32(size_t i) const
    {
        uint32_t v;
        std::memcpy(&v, reply.data() + 4 * i, 4);
        return v;
    }
};

Lbp16Identity identity()
{
    Lbp16Identity id;
    id.board_name = "7I96S";
    id.mac = {0x00, 0x60, 0x1B, 0x11, 0x22, 0x33};
    id.ip = 0xC0A80179; // 192.168.1.121
    id.ip_source = 1;
    id.fw_version = 16;
    return id;
}

void put16(std::vector<uint8_t> &v, unsigned x)
{
    v.push_back(static_cast<uint8_t>(x));
    v.push_back(static_cast<uint8_t>(x >> 8));
}

bool contains(const std::string &s, const char *what) { return s.find(what) != std::string::npos; }

void test_hm2_space()
{
    Rig r(identity());
    uint32_t w[4] = {0x11111111, 0x22222222, 0x33333333, 0x44444444};
    lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0x1000, 4, 1, w), 0);
    CHECK(!r.send(p)); // writes only: no reply
    CHECK(r.reply.empty());
    CHECK(r.board.last_inc);
    CHECK_EQ_INT(r.board.hm2_writes, 1);
    // no increment: four writes to one register, the last stays
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0x2000, 4, 0, w), 0);
    CHECK(!r.send(p));
    CHECK(!r.board.last_inc);
    uint32_t got;
    std::memcpy(&got, r.board.hm2 + 0x2000, 4);
    CHECK_EQ_INT(got, 0x44444444);
    std::memcpy(&got, r.board.hm2 + 0x2004, 4);
    CHECK_EQ_INT(got, 0);

    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0x1000, 4, 1), 0);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0x1004, 3, 0), 0);
    CHECK(r.send(p));
    CHECK_EQ_INT(r.reply.size(), 28);
    for (int i = 0; i < 4; i++)
        CHECK_EQ_INT(r.r32(i), w[i]);
    for (int i = 4; i < 7; i++)
        CHECK_EQ_INT(r.r32(i), 0x22222222);
    CHECK_EQ_INT(r.st(vb::eth::kStErrorFlags), 0);
}

void test_address_pointer()
{
    // Without bit 14 a command uses the space's pointer, left after the last
    // command at its final address (inc) or where it was (no inc).
    Rig r(identity());
    for (unsigned i = 0; i < 8; i++)
        std::memcpy(r.board.hm2 + 0x100 + 4 * i, &i, 4);
    std::vector<uint8_t> d;
    put16(d, 0x4282); // read 2 x 32 bit inc @0x100
    put16(d, 0x0100);
    put16(d, 0x0282); // read 2 more from the pointer (0x108)
    put16(d, 0x0201); // no inc @0x110, pointer stays
    put16(d, 0x0201);
    CHECK(r.send(d));
    CHECK_EQ_INT(r.reply.size(), 24);
    const unsigned want[6] = {0, 1, 2, 3, 4, 4};
    for (int i = 0; i < 6; i++)
        CHECK_EQ_INT(r.r32(i), want[i]);
    // pointers are per space: space 1 still at 0
    d.clear();
    put16(d, 0xC581); // write 1 x 16 bit space 1 inc @0x10
    put16(d, 0x0010);
    put16(d, 0xBEEF);
    put16(d, 0x0581); // read from the pointer: 0x12
    put16(d, 0x0201); // space 0 pointer: still 0x110
    CHECK(r.send(d));
    CHECK_EQ_INT(r.reply.size(), 6);
    CHECK_EQ_INT(r.r16(0), 0);
    uint32_t w4;
    std::memcpy(&w4, r.reply.data() + 2, 4);
    CHECK_EQ_INT(w4, 4);
    CHECK_EQ_INT(r.engine.word(1, 0x10), 0xBEEF);
    // the info area shows the pointer (word 3)
    d.clear();
    put16(d, 0x6581); // info read space 1, word 3
    put16(d, 0x0006);
    CHECK(r.send(d));
    CHECK_EQ_INT(r.r16(0), 0x14);
}

void test_small_spaces_rw()
{
    // Spaces 1 (Ethernet chip), 4 (timers), 6 (LBP16RW): 16-bit RW, inc/no inc.
    const unsigned spaces[3] = {1, 4, 6};
    for (unsigned s : spaces) {
        Rig r(identity());
        uint16_t v[3] = {0x0A0B, 0x0C0D, 0x0E0F};
        lbp16_pkt p;
        lbp16_reset(&p);
        unsigned base = s == 1 ? 0x40 : s == 4 ? 0x10 : 0x18; // plain memory words
        CHECK_EQ_INT(lbp16_add_write(&p, s, 2, static_cast<uint16_t>(base), s == 6 ? 1 : 3, 1,
                                     v),
                     0);
        CHECK_EQ_INT(lbp16_add_read(&p, s, 2, static_cast<uint16_t>(base), s == 6 ? 1 : 3, 1),
                     0);
        CHECK_EQ_INT(lbp16_add_read(&p, s, 2, static_cast<uint16_t>(base), 2, 0), 0);
        CHECK(r.send(p));
        if (s == 6) {
            CHECK_EQ_INT(r.reply.size(), 6);
            CHECK_EQ_INT(r.r16(0), 0x0A0B);
            CHECK_EQ_INT(r.r16(2), 0x0A0B);
        } else {
            CHECK_EQ_INT(r.reply.size(), 10);
            for (int i = 0; i < 3; i++)
                CHECK_EQ_INT(r.r16(i), v[i]);
            CHECK_EQ_INT(r.r16(3), 0x0A0B);
            CHECK_EQ_INT(r.r16(4), 0x0A0B);
        }
        // 32-bit and 8-bit elements are not allowed in 16-bit spaces
        uint16_t before = r.st(vb::eth::kStMemErrors);
        lbp16_reset(&p);
        CHECK_EQ_INT(lbp16_add_read(&p, s, 4, static_cast<uint16_t>(base), 1, 1), 0);
        CHECK(!r.send(p));
        CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), before + 1);
        lbp16_reset(&p);
        CHECK_EQ_INT(lbp16_add_read(&p, s, 1, static_cast<uint16_t>(base), 1, 1), 0);
        CHECK(!r.send(p));
        CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), before + 2);
        CHECK(contains(r.engine.last_error(), "no such memory or element size"));
    }
}

void test_eeprom()
{
    Rig r(identity());
    lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 2, 2, 2, 3, 1), 0);    // 0x4983 @2: MAC
    CHECK_EQ_INT(lbp16_add_read(&p, 2, 2, 0x10, 8, 1), 0); // name
    CHECK_EQ_INT(lbp16_add_read(&p, 2, 2, 0x20, 2, 1), 0); // IP low, high
    CHECK(r.send(p));
    CHECK_EQ_INT(r.reply.size(), 6 + 16 + 4);
    CHECK_EQ_INT(r.r16(0), 0x2233); // low word: MAC[4] MAC[5]
    CHECK_EQ_INT(r.r16(1), 0x1B11);
    CHECK_EQ_INT(r.r16(2), 0x0060);
    CHECK(std::memcmp(r.reply.data() + 6, "7I96S\0\0\0\0\0\0\0\0\0\0\0", 16) == 0);
    CHECK_EQ_INT(r.r16(11), 0x0179);
    CHECK_EQ_INT(r.r16(12), 0xC0A8);

    // a write without the key in the same datagram is refused
    uint16_t ip[2] = {0x0102, 0x0A00};
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 2, 2, 0x20, 2, 1, ip), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.st(vb::eth::kStWriteErrors), 1);
    CHECK_EQ_INT(r.st(vb::eth::kStErrorFlags) & 4, 4);
    CHECK(contains(r.engine.last_error(), "write refused"));
    CHECK_EQ_INT(r.engine.word(2, 0x20), 0x0179);
    // with the key first it is taken
    uint16_t key = vb::eth::kWriteEnableKey;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 6, 2, 0x1A, 1, 0, &key), 0);
    CHECK_EQ_INT(lbp16_add_write(&p, 2, 2, 0x20, 2, 1, ip), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.engine.word(2, 0x20), 0x0102);
    CHECK_EQ_INT(r.engine.word(2, 0x22), 0x0A00);
    // the key does not carry over to the next datagram
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 2, 2, 0x20, 1, 0, &key), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.st(vb::eth::kStWriteErrors), 2);
    CHECK_EQ_INT(r.engine.word(2, 0x20), 0x0102);
}

void test_flash_space()
{
    Rig r(identity());
    lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 3, 4, 8, 1, 0), 0); // 0x4E01 @8: flash ID
    CHECK(r.send(p));
    CHECK_EQ_INT(r.reply.size(), 4);
    CHECK_EQ_INT(r.r32(0), 0x16);
    // address register writes need no key; data writes do
    uint32_t a = 0x10000, d = 0xCAFEF00D;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 3, 4, 0, 1, 0, &a), 0);
    CHECK_EQ_INT(lbp16_add_write(&p, 3, 4, 4, 1, 0, &d), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.board.flash_regs[0], 0x10000);
    CHECK_EQ_INT(r.board.flash_regs[1], 0);
    CHECK_EQ_INT(r.st(vb::eth::kStWriteErrors), 1);
    uint16_t key = vb::eth::kWriteEnableKey;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 6, 2, 0x1A, 1, 0, &key), 0);
    CHECK_EQ_INT(lbp16_add_write(&p, 3, 4, 4, 1, 0, &d), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.board.flash_regs[1], 0xCAFEF00D);
    // 16-bit access and addresses past the four registers are refused
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 3, 2, 8, 1, 0), 0);
    CHECK(!r.send(p));
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 3, 4, 0x10, 1, 0), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), 2);
}

void test_timers_and_status_actions()
{
    Rig r(identity());
    lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 4, 2, 0, 1, 0), 0); // us time stamp
    uint16_t wait = 250;
    CHECK_EQ_INT(lbp16_add_write(&p, 4, 2, 2, 1, 0, &wait), 0);
    CHECK(r.send(p));
    CHECK_EQ_INT(r.r16(0), 0xABCD);
    CHECK_EQ_INT(r.board.waited_us, 250);
    // reset: a non-zero word at 0x1C; zero does nothing
    uint16_t zero = 0, one = 1, icap[3] = {0xFFFF, 0xAA99, 0x5566};
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 6, 2, 0x1C, 1, 0, &zero), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.board.resets, 0);
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 6, 2, 0x1C, 1, 0, &one), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.board.resets, 1);
    // ICAP port 0x1E: every word reaches the board in order (no increment)
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 6, 2, 0x1E, 3, 0, icap), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.board.icap.size(), 3);
    CHECK(r.board.icap == std::vector<uint16_t>({0xFFFF, 0xAA99, 0x5566}));
    // every datagram counts as received (5 so far + this one)
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 6, 2, 0x08, 2, 1), 0);
    CHECK(r.send(p));
    CHECK_EQ_INT(r.r16(0), 5);
    CHECK_EQ_INT(r.r16(1), 5);
    r.engine.count_tx(true);
    r.engine.count_tx(false);
    CHECK_EQ_INT(r.st(vb::eth::kStTxPackets), 1);
    CHECK_EQ_INT(r.st(vb::eth::kStTxUdp), 1);
    CHECK_EQ_INT(r.st(vb::eth::kStTxBad), 1);
}

void test_board_info_space()
{
    Rig r(identity());
    std::vector<uint8_t> d;
    put16(d, 0x5D88); // spec: read 8 x 16-bit board info inc from 0
    put16(d, 0x0000);
    put16(d, 0x5D83); // 0x10 LBP16 version, 0x12 firmware version, 0x14 IP source
    put16(d, 0x0010);
    CHECK(r.send(d));
    CHECK_EQ_INT(r.reply.size(), 22);
    CHECK(std::memcmp(r.reply.data(), "7I96S\0\0\0\0\0\0\0\0\0\0\0", 16) == 0);
    CHECK_EQ_INT(r.r16(8), 3);
    CHECK_EQ_INT(r.r16(9), 16);
    CHECK_EQ_INT(r.r16(10), 1);
    // read-only: a write is refused and counted
    uint16_t v = 0x4141;
    lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 7, 2, 0, 1, 0, &v), 0);
    CHECK(!r.send(p));
    CHECK_EQ_INT(r.st(vb::eth::kStWriteErrors), 1);
    CHECK_EQ_INT(r.engine.word(7, 0), 0x4937);
}

void test_info_areas()
{
    // spec 17.3: cookie 0x5A00+space, type/size, range, pointer, 8-char name
    struct Want {
        unsigned space, type_size, range;
        const char *name;
    };
    const Want want[] = {{0, 0x8104, 16, "HostMot2"}, {1, 0x8102, 8, "KSZ8851"},
                         {2, 0x8E02, 7, "EtherEEP"},  {3, 0x8F04, 0x8200, "FPGAFlsh"},
                         {4, 0x8202, 4, "Timers"},    {6, 0x8202, 4, "LBP16RW"},
                         {7, 0x0202, 4, "LBP16RO"}};
    Rig r(identity());
    for (const Want &w : want) {
        std::vector<uint8_t> d;
        put16(d, 0x6000u | w.space << 10 | 0x0100 | 0x80 | 8); // info, 16 bit, inc, 8
        put16(d, 0);
        CHECK(r.send(d));
        CHECK_EQ_INT(r.reply.size(), 16);
        CHECK_EQ_INT(r.r16(0), 0x5A00 + w.space);
        CHECK_EQ_INT(r.r16(1), w.type_size);
        CHECK_EQ_INT(r.r16(2), w.range);
        char name[9] = {};
        std::memcpy(name, r.reply.data() + 8, 8);
        CHECK_EQ_STR(name, w.name);
        CHECK_EQ_INT(r.engine.word(6, vb::eth::kStErrorFlags), 0);
    }
    // space 5 has no info area; info is 16-bit, read-only, 8 words long
    const unsigned bad[][2] = {{0x7581, 0}, {0x6681, 0}, {0x6081, 0}, {0x6188, 2}, {0x6189, 0}};
    unsigned mem_errors = 0;
    for (const auto &b : bad) {
        std::vector<uint8_t> d;
        put16(d, b[0]);
        put16(d, b[1]);
        CHECK(!r.send(d));
        CHECK(r.reply.empty());
        CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), ++mem_errors);
    }
    std::vector<uint8_t> d;
    put16(d, 0xE181);
    put16(d, 0);
    put16(d, 0);
    CHECK(!r.send(d));
    CHECK_EQ_INT(r.st(vb::eth::kStWriteErrors), 1);
    CHECK(contains(r.engine.last_error(), "info area"));
}

void test_missing_space_and_sizes()
{
    Rig r(identity());
    std::vector<uint8_t> d;
    put16(d, 0x5581); // space 5, 16 bit
    put16(d, 0);
    CHECK(!r.send(d));
    CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), 1);
    CHECK(contains(r.engine.last_error(), "space 5"));
    d.clear();
    put16(d, 0x4381); // space 0, 64-bit elements (size code 3): not offered
    put16(d, 0);
    CHECK(!r.send(d));
    d.clear();
    put16(d, 0x4181); // space 0, 16-bit: hm2 is 32-bit only
    put16(d, 0);
    CHECK(!r.send(d));
    CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), 3);
    CHECK_EQ_INT(r.board.hm2_reads, 0);
}

void test_ranges()
{
    Rig r(identity());
    struct Case {
        unsigned cmd, addr;
    };
    // unaligned, at the end, a span running past the end (inc), past 16 bits
    const Case bad[] = {{0x4201, 0x0002}, {0x4582, 0x00FE}, {0x4581, 0x0101},
                        {0x4282, 0xFFFC}, {0x5182, 0x001E}, {0x5981, 0x0020}};
    unsigned n = 0;
    for (const Case &c : bad) {
        std::vector<uint8_t> d;
        put16(d, c.cmd);
        put16(d, c.addr);
        CHECK(!r.send(d));
        CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), ++n);
    }
    CHECK_EQ_INT(r.board.hm2_reads, 0);
    // the last element exactly at the end is fine; no-inc never spans
    const Case good[] = {{0x42FF, 0xFE04}, {0x427F, 0xFFFC}, {0x5181, 0x001E}, {0x4981, 0x7E}};
    for (const Case &c : good) {
        std::vector<uint8_t> d;
        put16(d, c.cmd);
        put16(d, c.addr);
        CHECK(r.send(d));
    }
    CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), n);
}

void test_malformed()
{
    Rig r(identity());
    struct Case {
        std::vector<uint8_t> d;
        const char *why;
    };
    const Case cases[] = {
        {{}, "holds no command"},
        {{0x01}, "holds no command"},
        {{0x01, 0x59, 0x08, 0x00, 0x01}, "ends inside it"},  // a good read then 1 byte
        {{0x00, 0x42, 0x00, 0x00}, "element count 0"},      // count 0
        {{0x01, 0x42}, "address missing"},                  // bit 14, no address
        {{0x01, 0x42, 0x00}, "address missing"},            // half an address
        {{0x02, 0xC2, 0x00, 0x10, 1, 2, 3, 4}, "8 data bytes, datagram has 4"},
        {{0x81, 0xD9, 0x1A, 0x00}, "2 data bytes, datagram has 0"},
    };
    unsigned parse = 0;
    for (const Case &c : cases) {
        CHECK(!r.engine.handle(c.d.data(), c.d.size(), r.reply));
        CHECK(r.reply.empty());
        CHECK_EQ_INT(r.st(vb::eth::kStParseErrors), ++parse);
        if (!contains(r.engine.last_error(), c.why))
            std::fprintf(stderr, "  reason \"%s\" lacks \"%s\"\n", r.engine.last_error().c_str(),
                         c.why);
        CHECK(contains(r.engine.last_error(), c.why));
    }
    CHECK_EQ_INT(r.st(vb::eth::kStErrorFlags) & 1, 1);
    CHECK_EQ_INT(r.st(vb::eth::kStRxBad), 2); // the two without a command word
    CHECK_EQ_INT(r.st(vb::eth::kStRxPackets), 8);
    // the failing command is named by its word and byte offset
    std::vector<uint8_t> d = {0x01, 0x59, 0x08, 0x00, 0x00, 0x42, 0x00, 0x00};
    CHECK(!r.engine.handle(d.data(), d.size(), r.reply));
    CHECK(contains(r.engine.last_error(), "command 0x4200 at byte 4"));
    // a good datagram afterwards clears the reason and answers
    d.resize(4);
    CHECK(r.engine.handle(d.data(), d.size(), r.reply));
    CHECK_EQ_INT(r.reply.size(), 2);
    CHECK_EQ_STR(r.engine.last_error().c_str(), "");
}

void test_commands_before_failure_ran()
{
    Rig r(identity());
    uint32_t v = 0x5555AAAA;
    lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_write(&p, 0, 4, 0x0200, 1, 0, &v), 0);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0x0200, 1, 0), 0);
    CHECK_EQ_INT(lbp16_add_read(&p, 5, 2, 0, 1, 0), 0); // no space 5
    CHECK(!r.send(p));
    CHECK(r.reply.empty()); // no partial reply
    uint32_t got;
    std::memcpy(&got, r.board.hm2 + 0x200, 4);
    CHECK_EQ_INT(got, 0x5555AAAA);
}

void test_oversized_reply()
{
    // One datagram can carry 65507 bytes: 129 reads of 127 x 32 bits ask for
    // 65532.  Refused as a memory error before the board is touched.
    Rig r(identity());
    std::vector<uint8_t> d;
    for (int i = 0; i < 129; i++) {
        put16(d, 0x42FF);
        put16(d, 0x0000);
    }
    CHECK(!r.send(d));
    CHECK(r.reply.empty());
    CHECK(contains(r.engine.last_error(), "would not fit in one datagram"));
    CHECK_EQ_INT(r.st(vb::eth::kStMemErrors), 1);
    CHECK_EQ_INT(r.board.hm2_reads, 128);
    d.resize(4 * 128); // 65024 bytes: fits
    CHECK(r.send(d));
    CHECK_EQ_INT(r.reply.size(), 128 * 508);
}

void test_servo_cycle_round_trip()
{
    // The host's servo-cycle read packet answered by the engine passes the
    // host's reply check; a write packet's sequence number shows up in the
    // next read reply.
    Rig r(identity());
    uint32_t in = 0x89ABCDEF;
    std::memcpy(r.board.hm2 + 0x1000, &in, 4);
    lbp16_pkt w;
    lbp16_reset(&w);
    uint32_t out = 7;
    CHECK_EQ_INT(lbp16_add_write(&w, 0, 4, 0x1100, 1, 1, &out), 0);
    CHECK_EQ_INT(lbp16_add_write_tail(&w, 41), 0);
    CHECK(!r.send(w));
    lbp16_pkt p;
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 0, 4, 0x1000, 1, 1), 0);
    CHECK_EQ_INT(lbp16_add_read_tail(&p, 42), 0);
    CHECK(r.send(p));
    lbp16_reply_check c{};
    CHECK_EQ_INT(lbp16_check_read_reply(r.reply.data(), r.reply.size(), p.reply_len, 42, &c), 0);
    CHECK_EQ_INT(c.read_seq, 42);
    CHECK_EQ_INT(c.write_seq, 41);
    CHECK_EQ_INT(c.rx_packets, 2);
    CHECK_EQ_INT(r.r32(0), 0x89ABCDEF);
    CHECK_EQ_INT(lbp16_check_read_reply(r.reply.data(), r.reply.size(), p.reply_len, 43, &c),
                 -ESTALE);
    // synchronous tag
    lbp16_reset(&p);
    CHECK_EQ_INT(lbp16_add_read(&p, 7, 2, 0, 8, 1), 0);
    CHECK_EQ_INT(lbp16_add_sync_tag(&p, 0xA1B2C3D4u), 0);
    CHECK(r.send(p));
    CHECK_EQ_INT(lbp16_check_sync_reply(r.reply.data(), r.reply.size(), p.reply_len, 0xA1B2C3D4u),
                 0);
}

} // namespace

int main()
{
    RUN(test_hm2_space);
    RUN(test_address_pointer);
    RUN(test_small_spaces_rw);
    RUN(test_eeprom);
    RUN(test_flash_space);
    RUN(test_timers_and_status_actions);
    RUN(test_board_info_space);
    RUN(test_info_areas);
    RUN(test_missing_space_and_sizes);
    RUN(test_ranges);
    RUN(test_malformed);
    RUN(test_commands_before_failure_ran);
    RUN(test_oversized_reply);
    RUN(test_servo_cycle_round_trip);
    return check_summary();
}
