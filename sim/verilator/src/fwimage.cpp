// SPDX-License-Identifier: GPL-2.0-or-later
//
// fwimage.cpp - parse the virtual boards' firmware image (fwimage.h).
#include "fwimage.h"

#include <cerrno>
#include <cstdio>

namespace vb {

namespace {
uint32_t le32(const uint8_t *p)
{
    return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 |
           static_cast<uint32_t>(p[2]) << 16 | static_cast<uint32_t>(p[3]) << 24;
}

// A NUL-padded text field; false when it is not NUL terminated or holds
// non-printable bytes.
bool text_field(const uint8_t *p, size_t n, std::string &out)
{
    size_t len = 0;
    while (len < n && p[len] != 0)
        len++;
    if (len == n || len == 0)
        return false;
    for (size_t i = 0; i < len; i++)
        if (p[i] < 0x20 || p[i] > 0x7E)
            return false;
    out.assign(reinterpret_cast<const char *>(p), len);
    return true;
}
} // namespace

uint32_t crc32(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

int parse_fw_image(const uint8_t *p, size_t n, FwImage &img, std::string &err)
{
    char buf[160];
    if (n >= 4 && le32(p) != kFwMagic) {
        err = "not a virtual-board firmware image (bad magic; is this a real FPGA bitstream?)";
        return -EINVAL;
    }
    if (n < kFwImageSize) {
        std::snprintf(buf, sizeof buf,
                      "firmware image is truncated: %zu bytes, a virtual-board image has %zu",
                      n, kFwImageSize);
        err = buf;
        return -EINVAL;
    }
    if (le32(p + 4) != kFwVersion) {
        std::snprintf(buf, sizeof buf, "firmware image has format version %u, this vboard reads %u",
                      le32(p + 4), kFwVersion);
        err = buf;
        return -EINVAL;
    }
    uint32_t len = le32(p + 8);
    if (len != n) {
        std::snprintf(buf, sizeof buf, "firmware image is %s: header says %u bytes, got %zu",
                      n < len ? "truncated" : "longer than its header says", len, n);
        err = buf;
        return -EINVAL;
    }
    uint32_t want = le32(p + 64), got = crc32(p, 64);
    if (want != got) {
        std::snprintf(buf, sizeof buf,
                      "firmware image is corrupt: CRC-32 0x%08x, the image says 0x%08x", got,
                      want);
        err = buf;
        return -EINVAL;
    }
    if (!text_field(p + 16, 16, img.board) || !text_field(p + 32, 32, img.firmware)) {
        err = "firmware image has a malformed board or firmware name";
        return -EINVAL;
    }
    img.idrom_crc = le32(p + 12);
    return 0;
}

int match_fw_image(const uint8_t *p, size_t n, const std::string &board,
                   const std::vector<BuiltFw> &built, const char *id_label, std::string &err)
{
    FwImage img;
    int rc = parse_fw_image(p, n, img, err);
    if (rc)
        return rc;
    if (img.board != board) {
        err = "firmware image is for board " + img.board + ", this board is a " + board;
        return -EINVAL;
    }
    std::string names;
    for (size_t i = 0; i < built.size(); i++) {
        names += (i ? ", " : "") + built[i].name;
        if (built[i].name != img.firmware)
            continue;
        if (built[i].build_id != img.idrom_crc) {
            char buf[240];
            std::snprintf(buf, sizeof buf,
                          "firmware image %s does not match the Verilated firmware (%s 0x%08x, "
                          "built 0x%08x): image and vboard come from different builds",
                          img.firmware.c_str(), id_label, img.idrom_crc, built[i].build_id);
            err = buf;
            return -EINVAL;
        }
        return static_cast<int>(i);
    }
    err = "firmware image " + img.firmware + " is not built into this vboard for board " + board +
          " (built: " + names + ")";
    return -EINVAL;
}

} // namespace vb
