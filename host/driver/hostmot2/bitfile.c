/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _POSIX_C_SOURCE 200809L
/* Xilinx .BIT container (spec §18) and firmware file lookup. */
#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "hm2/bitfile.h"

static const uint8_t bit_header[13] = {0x00, 0x09, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F,
                                       0xF0, 0x0F, 0xF0, 0x00, 0x00, 0x01};

int hm2_bitfile_parse(const uint8_t *buf, size_t len, struct hm2_bitfile *bf, char *err,
                      size_t errlen)
{
    memset(bf, 0, sizeof(*bf));
    if (len < sizeof(bit_header) + 1) {
        snprintf(err, errlen, "bitfile is too short");
        return -EINVAL;
    }
    if (memcmp(buf, bit_header, sizeof(bit_header)) != 0) {
        snprintf(err, errlen, "bitfile has invalid header");
        return -EINVAL;
    }
    size_t pos = sizeof(bit_header);
    bool have_e = false;
    while (pos < len) {
        char tag = (char)buf[pos++];
        if (tag >= 'a' && tag <= 'd') {
            if (len - pos < 2) {
                snprintf(err, errlen, "bitfile chunk extends past end of firmware");
                return -EINVAL;
            }
            size_t n = ((size_t)buf[pos] << 8) | buf[pos + 1];
            pos += 2;
            if (n > len - pos) {
                snprintf(err, errlen, "bitfile chunk extends past end of firmware");
                return -EINVAL;
            }
            if (n == 0 || buf[pos + n - 1] != '\0') {
                snprintf(err, errlen, "bitfile small chunk is not NULL terminated");
                return -EINVAL;
            }
            const char *text = (const char *)(buf + pos);
            switch (tag) {
            case 'a': bf->design = text; break;
            case 'b': bf->part = text; break;
            case 'c': bf->date = text; break;
            default: bf->time = text; break;
            }
            pos += n;
        } else if (tag == 'e') {
            if (len - pos < 4) {
                snprintf(err, errlen, "bitfile chunk extends past end of firmware");
                return -EINVAL;
            }
            size_t n = ((size_t)buf[pos] << 24) | ((size_t)buf[pos + 1] << 16) |
                       ((size_t)buf[pos + 2] << 8) | buf[pos + 3];
            pos += 4;
            if (n > len - pos) {
                snprintf(err, errlen, "bitfile chunk extends past end of firmware");
                return -EINVAL;
            }
            bf->data = buf + pos;
            bf->size = (uint32_t)n;
            have_e = true;
            pos += n;
        } else {
            if (tag >= 0x20 && tag <= 0x7E)
                snprintf(err, errlen, "bitfile has unknown chunk '%c'", tag);
            else
                snprintf(err, errlen, "bitfile has unknown chunk '\\x%02x'", (unsigned char)tag);
            return -EINVAL;
        }
    }
    if (!bf->part) {
        snprintf(err, errlen, "bitfile lacks Part Name (chunk 'b')!");
        return -EINVAL;
    }
    if (!have_e) {
        snprintf(err, errlen, "bitfile lacks FPGA Config (part 'e')!");
        return -EINVAL;
    }
    return 0;
}

static bool name_is_safe(const char *name)
{
    if (name[0] == '\0' || name[0] == '/')
        return false;
    const char *p = name;
    while (*p) {
        const char *slash = strchr(p, '/');
        size_t n = slash ? (size_t)(slash - p) : strlen(p);
        if (n == 2 && p[0] == '.' && p[1] == '.')
            return false;
        if (!slash)
            break;
        p = slash + 1;
    }
    return true;
}

int hm2_firmware_find(const char *search_path, const char *name, char *out, size_t outlen)
{
    if (!name || !name_is_safe(name))
        return -EINVAL;
    const char *p = search_path ? search_path : "";
    while (*p) {
        const char *colon = strchr(p, ':');
        size_t n = colon ? (size_t)(colon - p) : strlen(p);
        if (n > 0) {
            int w = snprintf(out, outlen, "%.*s/%s", (int)n, p, name);
            struct stat st;
            if (w > 0 && (size_t)w < outlen && stat(out, &st) == 0 && S_ISREG(st.st_mode))
                return 0;
        }
        if (!colon)
            break;
        p = colon + 1;
    }
    return -ENOENT;
}

/* The build's own firmware directory, compiled in so that a `make` tree
 * finds its firmware without any environment variable. */
#ifndef HM2_BUILD_FIRMWARE_DIR
#define HM2_BUILD_FIRMWARE_DIR ""
#endif

const char *hm2_firmware_default_path(char *buf, size_t len)
{
    const char *env = getenv("HM2_FIRMWARE_PATH");
    if (env && *env) {
        snprintf(buf, len, "%s", env);
        return buf;
    }
    const char *build = getenv("HM_BUILD");
    const char *own = HM2_BUILD_FIRMWARE_DIR;
    size_t n = 0;
    buf[0] = 0;
    if (build && *build)
        n += (size_t)snprintf(buf + n, n < len ? len - n : 0, "%s/lib/firmware:", build);
    if (*own && n < len)
        n += (size_t)snprintf(buf + n, len - n, "%s:", own);
    if (n < len)
        snprintf(buf + n, len - n, "/lib/firmware");
    return buf;
}

int hm2_read_file(const char *path, size_t max, uint8_t **buf, size_t *len)
{
    *buf = NULL;
    *len = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return -errno;
    int r = 0;
    uint8_t *data = NULL;
    struct stat st;
    if (fstat(fileno(f), &st) != 0) {
        r = -errno;
        goto out;
    }
    if (!S_ISREG(st.st_mode) || (size_t)st.st_size > max) {
        r = -EFBIG;
        goto out;
    }
    size_t n = (size_t)st.st_size;
    data = malloc(n ? n : 1);
    if (!data) {
        r = -ENOMEM;
        goto out;
    }
    if (n && fread(data, 1, n, f) != n) {
        r = -EIO;
        free(data);
        data = NULL;
        goto out;
    }
    *buf = data;
    *len = n;
out:
    fclose(f);
    return r;
}
