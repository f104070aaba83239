// SPDX-License-Identifier: GPL-2.0-or-later
//
// libFuzzer target: the virtual Ethernet board's LBP16 command engine
// (sim/verilator/eth/lbp16.cpp) behind a fake board.  Any datagram runs or
// is refused (counted in the status space); a reply never holds more than
// the read commands asked for or one datagram can carry, a reply to send is
// never empty, and no access leaves the fake board's memories.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "lbp16.h"

namespace {

class FakeBoard final : public vb::eth::Lbp16Target {
  public:
    uint8_t hm2[0x10000] = {};
    uint32_t flash_addr = 0;
    bool hm2_read(uint32_t addr, unsigned count, bool inc, uint8_t *out) override
    {
        for (unsigned i = 0; i < count; i++) {
            uint32_t a = inc ? addr + 4 * i : addr;
            if (a + 4 > sizeof hm2)
                std::abort(); // the engine must check ranges first
            std::memcpy(out + 4 * i, hm2 + a, 4);
        }
        return true;
    }
    bool hm2_write(uint32_t addr, unsigned count, bool inc, const uint8_t *data) override
    {
        for (unsigned i = 0; i < count; i++) {
            uint32_t a = inc ? addr + 4 * i : addr;
            if (a + 4 > sizeof hm2)
                std::abort();
            std::memcpy(hm2 + a, data + 4 * i, 4);
        }
        return true;
    }
    bool flash_read(uint32_t reg, uint32_t &v) override
    {
        v = reg == 0 ? flash_addr : 0xFFFFFFFFu;
        return reg <= 8;
    }
    bool flash_write(uint32_t reg, uint32_t v, bool enabled) override
    {
        if (reg == 0)
            flash_addr = v;
        return reg == 0 || enabled;
    }
    uint64_t now_us() const override { return 1234; }
    void wait_us(unsigned) override {}
    void reset() override {}
    void icap_word(uint16_t) override {}
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static FakeBoard board;
    vb::eth::Lbp16Identity id;
    id.board_name = "7I96S";
    static vb::eth::Lbp16 engine(board, id);
    std::vector<uint8_t> reply;
    bool send = engine.handle(data, size, reply);
    // a reply holds at most 127 elements of 8 bytes per 2-byte command
    if (reply.size() > (size / 2) * 127 * 8)
        std::abort();
    if (reply.size() > 65507 || (send && reply.empty()))
        std::abort();
    return 0;
}
