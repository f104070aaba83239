// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_config.cpp - the fast model's view of a firmware, from its IDROM.
#include "fast_config.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace vb::fast {

namespace {
constexpr uint32_t kMaxModules = 32;

// The module versions whose Verilog the models transcribe (hdl/hostmot2).
bool covered_version(uint8_t gtag, uint8_t version)
{
    switch (gtag) {
    case kTagWatchdog:
    case kTagIoPort:
    case kTagPwmGen:
    case kTagLed:
        return version == 0;
    case kTagEncoder:
        return version == 2 || version == 0x83;
    case kTagStepGen:
        return version == 2 || version == 0x42;
    default:
        return false;
    }
}

bool covered(uint8_t gtag)
{
    return gtag == kTagWatchdog || gtag == kTagIoPort || gtag == kTagEncoder ||
           gtag == kTagStepGen || gtag == kTagPwmGen || gtag == kTagLed;
}
} // namespace

std::string tag_name(uint8_t gtag)
{
    switch (gtag) {
    case 1: return "HM2DPLL";
    case kTagWatchdog: return "Watchdog";
    case kTagIoPort: return "IOPort";
    case kTagEncoder: return "Encoder";
    case kTagStepGen: return "StepGen";
    case kTagPwmGen: return "PWMGen";
    case 7: return "SPI";
    case 8: return "SSI";
    case 9: return "UARTTX";
    case 10: return "UARTRX";
    case 12: return "MuxedEncoder";
    case 13: return "MuxedEncoderSel";
    case 14: return "BSPI";
    case 15: return "DBSPI";
    case 18: return "TPPWM";
    case 19: return "WaveGen";
    case 23: return "BISS";
    case 24: return "FABS";
    case 0xC0: return "LBP16 (XLAT)";
    case 0xC1: return "SSerial";
    case kTagLed: return "LED";
    default: {
        char b[16];
        std::snprintf(b, sizeof b, "tag 0x%02x", gtag);
        return b;
    }
    }
}

const ModuleDesc *Config::find(uint8_t gtag) const
{
    for (const ModuleDesc &m : modules)
        if (m.gtag == gtag)
            return &m;
    return nullptr;
}

int parse_config(const uint32_t *words, Config &cfg, std::string &err)
{
    std::memcpy(cfg.idrom, words, sizeof cfg.idrom);
    uint32_t md_off = words[1], pd_off = words[2];
    if (md_off % 4 || pd_off % 4 || md_off / 4 >= 256 || pd_off / 4 >= 256) {
        err = "fast model: IDROM module/pin descriptor offsets " + std::to_string(md_off) + "/" +
              std::to_string(pd_off) + " are outside the 1 KiB IDROM";
        return -EINVAL;
    }
    cfg.io_ports = words[7];
    cfg.io_width = words[8];
    cfg.port_width = words[9];
    cfg.clock_low_hz = words[10];
    cfg.clock_high_hz = words[11];
    if (cfg.io_width == 0 || cfg.io_width > 144 || cfg.port_width == 0 || cfg.port_width > 32 ||
        cfg.io_ports * cfg.port_width != cfg.io_width || pd_off / 4 + cfg.io_width > 256 ||
        cfg.clock_low_hz == 0) {
        err = "fast model: IDROM has IOPorts " + std::to_string(cfg.io_ports) + ", IOWidth " +
              std::to_string(cfg.io_width) + ", PortWidth " + std::to_string(cfg.port_width) +
              ", ClockLow " + std::to_string(cfg.clock_low_hz) + ": not a consistent board";
        return -EINVAL;
    }
    cfg.modules.clear();
    for (uint32_t i = 0; i < kMaxModules; i++) {
        uint32_t w = md_off / 4 + 3 * i;
        if (w + 2 >= 256 || (words[w] & 0xff) == 0)
            break;
        ModuleDesc m;
        m.gtag = static_cast<uint8_t>(words[w]);
        m.version = static_cast<uint8_t>(words[w] >> 8);
        m.clock_tag = static_cast<uint8_t>(words[w] >> 16);
        m.instances = static_cast<uint8_t>(words[w] >> 24);
        m.base = static_cast<uint16_t>(words[w + 1]);
        m.registers = static_cast<uint8_t>(words[w + 1] >> 16);
        if (!covered(m.gtag) || !covered_version(m.gtag, m.version)) {
            char v[8];
            std::snprintf(v, sizeof v, "0x%02x", m.version);
            err = "the fast model does not cover module " + tag_name(m.gtag) +
                  (covered(m.gtag) ? std::string(" version ") + v : std::string()) +
                  " (module descriptor " + std::to_string(i) +
                  "); run this firmware with --model rtl";
            return -ENOTSUP;
        }
        if (m.base & 0xff) {
            err = "fast model: module " + tag_name(m.gtag) + " base address 0x" +
                  std::to_string(m.base) + " is not on a 256-byte page";
            return -EINVAL;
        }
        cfg.modules.push_back(m);
    }
    if (!cfg.find(kTagIoPort) || !cfg.find(kTagWatchdog)) {
        err = "fast model: the IDROM lists no IOPort or no Watchdog module";
        return -EINVAL;
    }
    cfg.pins.assign(cfg.io_width, PinDesc{});
    for (uint32_t p = 0; p < cfg.io_width; p++) {
        uint32_t w = words[pd_off / 4 + p];
        cfg.pins[p].sec_pin = static_cast<uint8_t>(w);
        cfg.pins[p].sec_tag = static_cast<uint8_t>(w >> 8);
        cfg.pins[p].sec_unit = static_cast<uint8_t>(w >> 16);
    }
    return 0;
}

} // namespace vb::fast
