/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * libFuzzer target: the .BIT container parser of the hostmot2 driver
 * (host/driver/hostmot2/bitfile.c).  Any input either parses, with every
 * chunk inside the input and the text chunks NUL-terminated there, or is
 * refused with a message; nothing reads outside the input.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/bitfile.h"

static void inside(const uint8_t *base, size_t n, const void *p, size_t len)
{
    const uint8_t *q = p;
    if (q < base || q + len > base + n)
        abort();
}

static void text_inside(const uint8_t *base, size_t n, const char *s)
{
    if (!s)
        return;
    inside(base, n, s, 1);
    size_t room = (size_t)(base + n - (const uint8_t *)s);
    if (!memchr(s, 0, room))
        abort(); /* not terminated inside the input */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct hm2_bitfile bf;
    char err[256];
    memset(err, 0x55, sizeof err);
    if (hm2_bitfile_parse(data, size, &bf, err, sizeof err) != 0) {
        if (!memchr(err, 0, sizeof err) || err[0] == 0)
            abort(); /* a refusal always says why */
        return 0;
    }
    if (!bf.part || !bf.data)
        abort();
    text_inside(data, size, bf.design);
    text_inside(data, size, bf.part);
    text_inside(data, size, bf.date);
    text_inside(data, size, bf.time);
    if (bf.size)
        inside(data, size, bf.data, bf.size);
    return 0;
}
