/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * test_cfgflash.c - hm2_flash_reload against a fake llio whose flash
 * registers answer as a Mesa firmware's: 0x70 with DAV set, 0x74 the
 * M25P16's signature, 0x78 the ICAP register.  The reference is what
 * Debian's mesaflash 3.4.6 does (its disassembly, recorded in
 * spec/hostmot2.md "Configuration flash"): it reads 0x78 and wants
 * 0x1CAB1CAB, else "Active firmware too old to support --reload"; then it
 * writes 14 words to 0x78, 1 ms apart: FFFF FFFF AA99 5566 3261 0000 3281
 * 0B00|fallback 30A1 000E 2000 2000 2000 2000.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <string.h>

#include "check.h"
#include "hm2/cfgflash.h"

struct fake {
    hm2_llio_t llio; /* first */
    uint32_t icap_read;
    uint32_t icap[32];
    int nicap;
    uint64_t waited_ns;
};

static int fake_read(hm2_llio_t *l, uint32_t addr, void *buf, size_t size)
{
    struct fake *f = (struct fake *)l;
    uint32_t *w = buf;
    for (size_t i = 0; i < size / 4; i++) {
        uint32_t a = addr + 4 * (uint32_t)i;
        w[i] = a == 0x70 ? 0x04u : a == 0x74 ? 0x14u : a == 0x78 ? f->icap_read : 0u;
    }
    return 0;
}

static int fake_write(hm2_llio_t *l, uint32_t addr, const void *buf, size_t size)
{
    struct fake *f = (struct fake *)l;
    uint32_t v;
    if (size != 4)
        return -EINVAL;
    memcpy(&v, buf, 4);
    if (addr == 0x78 && f->nicap < 32)
        f->icap[f->nicap++] = v;
    return 0;
}

static void fake_delay(void *ctx, uint64_t ns)
{
    ((struct fake *)ctx)->waited_ns += ns;
}

static void setup(struct fake *f, struct hm2_flash_io *io, uint32_t icap)
{
    memset(f, 0, sizeof(*f));
    memset(io, 0, sizeof(*io));
    strcpy(f->llio.name, "hm2_5i25.0");
    f->llio.read = fake_read;
    f->llio.write = fake_write;
    f->icap_read = icap;
    io->llio = &f->llio;
    io->delay_ns = fake_delay;
    io->delay_ctx = f;
}

static void test_identify(void)
{
    struct fake f;
    struct hm2_flash_io io;
    setup(&f, &io, 0);
    CHECK_EQ_INT(hm2_flash_identify(&io), 0);
    CHECK_EQ_INT(io.signature, 0x14);
    CHECK_EQ_INT(io.size, 2 << 20);
    CHECK_EQ_INT(io.sector, 0x10000);
}

static void test_reload_refused_without_cookie(void)
{
    struct fake f;
    struct hm2_flash_io io;
    setup(&f, &io, 0x00000000u);
    CHECK_EQ_INT(hm2_flash_reload(&io, 0), -ENOTSUP);
    CHECK(strstr(io.err, "Active firmware too old to support --reload") != NULL);
    CHECK(strstr(io.err, "hm2_5i25.0") != NULL);
    CHECK_EQ_INT(f.nicap, 0); /* nothing written */
}

static void test_reload_words(void)
{
    static const uint32_t want[14] = {0xFFFF, 0xFFFF, 0xAA99, 0x5566, 0x3261, 0x0000, 0x3281,
                                      0x0B00, 0x30A1, 0x000E, 0x2000, 0x2000, 0x2000, 0x2000};
    for (int fb = 0; fb <= 1; fb++) {
        struct fake f;
        struct hm2_flash_io io;
        setup(&f, &io, 0x1CAB1CABu);
        CHECK_EQ_INT(hm2_flash_reload(&io, fb), 0);
        CHECK_EQ_INT(f.nicap, 14);
        for (int i = 0; i < 14; i++)
            CHECK_EQ_INT(f.icap[i], i == 7 ? want[i] | (uint32_t)fb : want[i]);
        CHECK(f.waited_ns >= 14 * 1000000ull); /* 1 ms per word */
    }
}

int main(void)
{
    RUN(test_identify);
    RUN(test_reload_refused_without_cookie);
    RUN(test_reload_words);
    return check_summary();
}
