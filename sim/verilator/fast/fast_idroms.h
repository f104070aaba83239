// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_idroms.h - the IDROM image of every local-bus firmware in the build
// (generated fast_idroms.cpp, from tools/hm2gen's .idrom.hex files).
#ifndef VBOARD_FAST_IDROMS_H
#define VBOARD_FAST_IDROMS_H

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace vb::fast {

struct FastIdrom {
    const char *board;
    const char *firmware;
    const uint32_t *words; // 256
};

extern const FastIdrom kFastIdroms[];
extern const size_t kNumFastIdroms;

inline const uint32_t *find_idrom(const char *board, const char *firmware)
{
    for (size_t i = 0; i < kNumFastIdroms; i++)
        if (!std::strcmp(kFastIdroms[i].board, board) &&
            !std::strcmp(kFastIdroms[i].firmware, firmware))
            return kFastIdroms[i].words;
    return nullptr;
}

} // namespace vb::fast

#endif // VBOARD_FAST_IDROMS_H
