/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * bitfile.h - Xilinx .BIT container parsing and firmware file lookup.
 *
 * A .BIT file is a 13-byte fixed header followed by tagged chunks: 'a'
 * design name, 'b' part name, 'c' date, 'd' time (2-byte big-endian length,
 * NUL-terminated text) and 'e' the bitstream (4-byte big-endian length).
 * The virtual boards' firmware uses the same container.  See docs/hostmot2.md.
 */
#ifndef HM2_BITFILE_H
#define HM2_BITFILE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_FIRMWARE_NAME_MAX 30

struct hm2_bitfile {
    /* Point into the parsed file's bytes (which the caller keeps alive);
     * NULL when the chunk is absent ('b' and 'e' are always present after a
     * successful parse). */
    const char *design;
    const char *part;
    const char *date;
    const char *time;
    const uint8_t *data; /* 'e' chunk, as in the file (MSB-first bytes) */
    uint32_t size;
};

/* Parse a .BIT image.  0 on success; -EINVAL on a malformed file, with the
 * LinuxCNC wording ("bitfile is too short", "bitfile has invalid header",
 * ...) in err. */
int hm2_bitfile_parse(const uint8_t *buf, size_t len, struct hm2_bitfile *bf, char *err,
                      size_t errlen);

/* Reverse the bit order of one byte (bit 7 <-> bit 0, ...): the order in
 * which the hm2 parallel configuration ports take bitstream bytes. */
static inline uint8_t hm2_bitfile_reverse(uint8_t b)
{
    b = (uint8_t)(((b & 0xF0u) >> 4) | ((b & 0x0Fu) << 4));
    b = (uint8_t)(((b & 0xCCu) >> 2) | ((b & 0x33u) << 2));
    b = (uint8_t)(((b & 0xAAu) >> 1) | ((b & 0x55u) << 1));
    return b;
}

/* Find `name` (relative, e.g. "hm2/5i20/SVST8_4.BIT") in a colon-separated
 * search path.  Writes the full path to out and returns 0, or -ENOENT.
 * Names that are absolute or contain ".." components are refused
 * (-EINVAL): firmware comes from the search path only. */
int hm2_firmware_find(const char *search_path, const char *name, char *out, size_t outlen);

/* The search path in effect: $HM2_FIRMWARE_PATH if set, else
 * "[$HM_BUILD/lib/firmware:]<this build>/lib/firmware:/lib/firmware"
 * ($HM_BUILD when set; the build's own directory is compiled in). */
const char *hm2_firmware_default_path(char *buf, size_t len);

/* Read a whole file (at most max bytes) into a malloc'd buffer. */
int hm2_read_file(const char *path, size_t max, uint8_t **buf, size_t *len);

#ifdef __cplusplus
}
#endif

#endif /* HM2_BITFILE_H */
