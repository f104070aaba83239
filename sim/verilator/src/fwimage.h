// SPDX-License-Identifier: GPL-2.0-or-later
//
// fwimage.h - the virtual boards' firmware image: the payload of a .BIT
// file's 'e' chunk (tools/vbfw writes them at build time; docs/vboard.md
// "Firmware files").  Little-endian:
//
//   off  size  field
//     0     4  magic "VBFW"
//     4     4  format version (1)
//     8     4  length: bytes of the whole image, this header and CRC included
//    12     4  IDROM CRC-32 of the generated firmware (identifies the build)
//    16    16  board name, NUL padded ("5i20")
//    32    32  firmware name, NUL padded ("SVST8_4")
//    64     4  CRC-32 (zlib polynomial) of bytes 0..63
//
// An image on a real FPGA would be a bitstream; here it names which of the
// Verilated firmwares to run and proves the file is whole.
#ifndef VBOARD_FWIMAGE_H
#define VBOARD_FWIMAGE_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vb {

constexpr uint32_t kFwMagic = 0x57464256u; // "VBFW"
constexpr uint32_t kFwVersion = 1;
constexpr size_t kFwImageSize = 68;

struct FwImage {
    std::string board;
    std::string firmware;
    uint32_t idrom_crc = 0;
};

uint32_t crc32(const uint8_t *p, size_t n);

// Parse and check an image (length, magic, version, CRC).  0, or -EINVAL
// with the reason.  Board and firmware matching is the board's job.
int parse_fw_image(const uint8_t *p, size_t n, FwImage &img, std::string &err);

// A firmware a board of this vboard can run, as an uploaded image must name
// it: its name and the build id the image must carry (the IDROM CRC of an
// hm2 firmware, the design id of a Pluto firmware).
struct BuiltFw {
    std::string name;
    uint32_t build_id;
};

// Which of `built` the image for `board` selects: its index, or -EINVAL
// with the reason (not an image, another board, a firmware this vboard
// does not have, another build; `id_label` names the build id in the
// message).  Every board's configuration path checks images with this.
int match_fw_image(const uint8_t *p, size_t n, const std::string &board,
                   const std::vector<BuiltFw> &built, const char *id_label, std::string &err);

} // namespace vb

#endif // VBOARD_FWIMAGE_H
