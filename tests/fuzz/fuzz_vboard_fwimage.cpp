// SPDX-License-Identifier: GPL-2.0-or-later
//
// libFuzzer target: the virtual board's firmware image check
// (sim/verilator/src/fwimage.cpp), which judges every image a host uploads:
// a Pluto-P passive-serial upload and the 'e' chunk of an hm2 .BIT alike.
// An image either parses (exactly kFwImageSize bytes, good CRC) or is
// refused with a reason.
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fwimage.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vb::FwImage img;
    std::string err;
    int r = vb::parse_fw_image(data, size, img, err);
    if (r == 0) {
        if (size < vb::kFwImageSize || img.board.size() > 16 || img.firmware.size() > 32)
            std::abort();
    } else if (r != -EINVAL || err.empty()) {
        std::abort();
    }
    return 0;
}
