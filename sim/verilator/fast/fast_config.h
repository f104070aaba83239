// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_config.h - what the fast board model (fast_model.h) knows about a
// firmware, read from the firmware's IDROM image (the words tools/hm2gen
// writes into the firmware, word k at hm2 address 0x400 + 4k): clocks, I/O
// ports, the module descriptors (tag, instances, base address) and the pin
// descriptors (which module unit and pin drives or reads each I/O pin).
// The same image is in the RTL, so both models come from one description.
#ifndef VBOARD_FAST_CONFIG_H
#define VBOARD_FAST_CONFIG_H

#include <cstdint>
#include <string>
#include <vector>

namespace vb::fast {

// hm2 general tags (spec/hostmot2.md): the modules the fast model covers.
enum Gtag : uint8_t {
    kTagWatchdog = 2,
    kTagIoPort = 3,
    kTagEncoder = 4,
    kTagStepGen = 5,
    kTagPwmGen = 6,
    kTagLed = 128,
};

struct ModuleDesc {
    uint8_t gtag = 0;
    uint8_t version = 0;
    uint8_t clock_tag = 0;
    uint8_t instances = 0;
    uint16_t base = 0;
    uint8_t registers = 0;
};

struct PinDesc {
    uint8_t sec_pin = 0;  // bit 7: output of the secondary module
    uint8_t sec_tag = 0;  // 0: GPIO only
    uint8_t sec_unit = 0;
};

struct Config {
    uint32_t idrom[256] = {};
    uint32_t clock_low_hz = 0, clock_high_hz = 0;
    uint32_t io_ports = 0, io_width = 0, port_width = 0;
    std::vector<ModuleDesc> modules;
    std::vector<PinDesc> pins; // io_width entries
    const ModuleDesc *find(uint8_t gtag) const;
};

// The name of a module tag ("Encoder", or "tag 0xNN" when unknown).
std::string tag_name(uint8_t gtag);

// Parse `words` (256 IDROM words).  Returns 0, or -EINVAL with the reason
// (a malformed image), or -ENOTSUP naming the first module the fast model
// does not cover ("the fast model does not cover module SSerial ...").
int parse_config(const uint32_t *words, Config &cfg, std::string &err);

} // namespace vb::fast

#endif // VBOARD_FAST_CONFIG_H
