/* SPDX-License-Identifier: GPL-2.0-or-later */
/* cfgflash.c - SPI configuration flash through the hm2 flash registers
 * (hm2/cfgflash.h). */
#define _POSIX_C_SOURCE 200809L
#include "hm2/cfgflash.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

enum {
    SPI_WRSR = 0x01,
    SPI_PP = 0x02,
    SPI_READ = 0x03,
    SPI_RDSR = 0x05,
    SPI_WREN = 0x06,
    SPI_RDID = 0x9F,
    SPI_RES = 0xAB,
    SPI_SE = 0xD8,
    SR_WIP = 0x01,
    SR_WEL = 0x02,
};

#define DAV_POLLS 1000
#define PP_TIMEOUT_NS 50000000ull       /* 50 ms: 10x the part's maximum */
#define SE_TIMEOUT_NS 10000000000ull    /* 10 s: the part's maximum is 3 s */

static int fail(struct hm2_flash_io *io, int rc, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int fail(struct hm2_flash_io *io, int rc, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(io->err, sizeof(io->err), fmt, ap);
    va_end(ap);
    return rc;
}

static int reg_write(struct hm2_flash_io *io, uint32_t addr, uint32_t v)
{
    int r = io->llio->write(io->llio, addr, &v, sizeof(v));
    if (r)
        return fail(io, r, "%s: write of flash register 0x%04X failed (%s)", io->llio->name,
                    addr, strerror(-r));
    return 0;
}

static int cs(struct hm2_flash_io *io, int active)
{
    return reg_write(io, HM2_FLASH_REG_CTRL, active ? 0u : 1u);
}

/* Shift one byte out and in: write the data register, then read control and
 * data together until the control register says the byte is there. */
static int xfer(struct hm2_flash_io *io, uint8_t out, uint8_t *in)
{
    int r = reg_write(io, HM2_FLASH_REG_DATA, out);
    if (r)
        return r;
    io->bytes_shifted++;
    for (int i = 0; i < DAV_POLLS; i++) {
        uint32_t v[2];
        r = io->llio->read(io->llio, HM2_FLASH_REG_CTRL, v, sizeof(v));
        if (r)
            return fail(io, r, "%s: read of the flash registers failed (%s)", io->llio->name,
                        strerror(-r));
        if (v[0] & HM2_FLASH_DAV) {
            if (in)
                *in = (uint8_t)v[1];
            return 0;
        }
    }
    return fail(io, -ETIMEDOUT,
                "%s: timeout waiting for SPI data (the firmware's flash interface does not "
                "answer; does it have one?)", io->llio->name);
}

/* One SPI frame: command bytes out, then n bytes in. */
static int frame(struct hm2_flash_io *io, const uint8_t *out, size_t nout, uint8_t *in, size_t nin)
{
    int r = cs(io, 1);
    for (size_t i = 0; !r && i < nout; i++)
        r = xfer(io, out[i], NULL);
    for (size_t i = 0; !r && i < nin; i++)
        r = xfer(io, 0, &in[i]);
    int r2 = cs(io, 0);
    return r ? r : r2;
}

static int read_status(struct hm2_flash_io *io, uint8_t *sr)
{
    uint8_t cmd = SPI_RDSR;
    return frame(io, &cmd, 1, sr, 1);
}

static int wait_ready(struct hm2_flash_io *io, uint64_t poll_ns, uint64_t timeout_ns,
                      const char *what, uint32_t addr)
{
    for (uint64_t waited = 0;; waited += poll_ns) {
        uint8_t sr;
        int r = read_status(io, &sr);
        if (r)
            return r;
        if (!(sr & SR_WIP))
            return 0;
        if (waited >= timeout_ns)
            return fail(io, -ETIMEDOUT, "%s: flash still busy %.1f s after %s at 0x%06X",
                        io->llio->name, (double)waited / 1e9, what, addr);
        io->delay_ns(io->delay_ctx, poll_ns);
    }
}

static int write_enable(struct hm2_flash_io *io, const char *what, uint32_t addr)
{
    uint8_t cmd = SPI_WREN, sr = 0;
    int r = frame(io, &cmd, 1, NULL, 0);
    if (!r)
        r = read_status(io, &sr);
    if (r)
        return r;
    if (!(sr & SR_WEL))
        return fail(io, -EIO, "%s: the flash did not enable writing for %s at 0x%06X "
                              "(status 0x%02X)", io->llio->name, what, addr, sr);
    if (sr & 0x1C)
        return fail(io, -EACCES, "%s: the flash is write protected (status 0x%02X, block "
                                 "protect bits set); %s at 0x%06X refused", io->llio->name, sr,
                    what, addr);
    return 0;
}

uint32_t hm2_flash_size_of(uint8_t sig)
{
    return sig >= 0x10 && sig <= 0x16 ? (128u * 1024u) << (sig - 0x10) : 0;
}

uint32_t hm2_flash_sector_of(uint8_t sig)
{
    return sig == 0x10 ? 0x8000u : HM2_FLASH_SECTOR;
}

const char *hm2_flash_size_text(uint8_t sig)
{
    static const char *const t[] = {"1 Mbit", "2 Mbit", "4 Mbit", "8 Mbit",
                                    "16 Mbit", "32 Mbit", "64 Mbit"};
    return sig >= 0x10 && sig <= 0x16 ? t[sig - 0x10] : "unknown";
}

int hm2_flash_identify(struct hm2_flash_io *io)
{
    uint8_t cmd[4] = {SPI_RES, 0, 0, 0}, sig = 0;
    int r = io->ops ? io->ops->identify(io, &sig) : frame(io, cmd, sizeof(cmd), &sig, 1);
    if (r)
        return r;
    io->signature = sig;
    io->size = hm2_flash_size_of(sig);
    io->sector = hm2_flash_sector_of(sig);
    if (!io->size)
        return fail(io, -ENODEV, "%s: unknown flash (electronic signature 0x%02X)",
                    io->llio->name, sig);
    return 0;
}

int hm2_flash_jedec(struct hm2_flash_io *io, uint8_t id[3])
{
    uint8_t cmd = SPI_RDID;
    if (io->ops)
        return fail(io, -ENOTSUP, "%s: no JEDEC ID through this interface", io->llio->name);
    return frame(io, &cmd, 1, id, 3);
}

static int check_range(struct hm2_flash_io *io, uint32_t addr, uint32_t n)
{
    if (!io->size)
        return fail(io, -EINVAL, "flash not identified");
    if (addr > io->size || n > io->size - addr)
        return fail(io, -EINVAL, "%s: range 0x%06X..0x%06X is outside the %u-byte flash",
                    io->llio->name, addr, addr + n, io->size);
    return 0;
}

static void progress(struct hm2_flash_io *io, const char *phase, uint32_t done, uint32_t total)
{
    if (io->progress)
        io->progress(io->progress_ctx, phase, done, total);
}

static int read_chunk(struct hm2_flash_io *io, uint32_t a, uint8_t *buf, uint32_t len)
{
    if (io->ops)
        return io->ops->read(io, a, buf, len);
    uint8_t cmd[4] = {SPI_READ, (uint8_t)(a >> 16), (uint8_t)(a >> 8), (uint8_t)a};
    return frame(io, cmd, sizeof(cmd), buf, len);
}

int hm2_flash_read(struct hm2_flash_io *io, uint32_t addr, uint8_t *buf, uint32_t n)
{
    int r = check_range(io, addr, n);
    const uint32_t chunk = 4096;
    for (uint32_t done = 0; !r && done < n; done += chunk) {
        uint32_t len = n - done < chunk ? n - done : chunk;
        uint32_t a = addr + done;
        r = read_chunk(io, a, buf + done, len);
        progress(io, "Reading", done + len, n);
    }
    return r;
}

static int erase_sector(struct hm2_flash_io *io, uint32_t addr)
{
    if (io->ops)
        return io->ops->erase_sector(io, addr);
    int r = write_enable(io, "sector erase", addr);
    uint8_t cmd[4] = {SPI_SE, (uint8_t)(addr >> 16), (uint8_t)(addr >> 8), (uint8_t)addr};
    if (!r)
        r = frame(io, cmd, sizeof(cmd), NULL, 0);
    if (!r)
        r = wait_ready(io, 10000000ull, SE_TIMEOUT_NS, "sector erase", addr);
    return r;
}

static int program_page(struct hm2_flash_io *io, uint32_t addr, const uint8_t *data, uint32_t n)
{
    if (io->ops)
        return io->ops->program_page(io, addr, data, n);
    int r = write_enable(io, "page program", addr);
    if (r)
        return r;
    uint8_t cmd[4] = {SPI_PP, (uint8_t)(addr >> 16), (uint8_t)(addr >> 8), (uint8_t)addr};
    r = cs(io, 1);
    for (size_t i = 0; !r && i < sizeof(cmd); i++)
        r = xfer(io, cmd[i], NULL);
    for (uint32_t i = 0; !r && i < n; i++)
        r = xfer(io, data[i], NULL);
    int r2 = cs(io, 0);
    if (r || r2)
        return r ? r : r2;
    return wait_ready(io, 100000ull, PP_TIMEOUT_NS, "page program", addr);
}

int hm2_flash_write(struct hm2_flash_io *io, uint32_t addr, const uint8_t *data, uint32_t n)
{
    int r = check_range(io, addr, n);
    if (r)
        return r;
    uint32_t sec = io->sector ? io->sector : HM2_FLASH_SECTOR;
    if (addr % sec)
        return fail(io, -EINVAL, "flash write at 0x%06X: not at a sector boundary", addr);
    uint32_t sectors = (n + sec - 1) / sec;
    for (uint32_t s = 0; s < sectors; s++) {
        if ((r = erase_sector(io, addr + s * sec)))
            return r;
        progress(io, "Erasing", (s + 1) * sec, sectors * sec);
    }
    for (uint32_t done = 0; done < n; done += HM2_FLASH_PAGE) {
        uint32_t len = n - done < HM2_FLASH_PAGE ? n - done : HM2_FLASH_PAGE;
        if ((r = program_page(io, addr + done, data + done, len)))
            return r;
        progress(io, "Programming", done + len, n);
    }
    return 0;
}

int hm2_flash_verify(struct hm2_flash_io *io, uint32_t addr, const uint8_t *data, uint32_t n,
                     uint32_t *bad_addr)
{
    int r = check_range(io, addr, n);
    const uint32_t chunk = 4096;
    uint8_t buf[4096];
    for (uint32_t done = 0; !r && done < n; done += chunk) {
        uint32_t len = n - done < chunk ? n - done : chunk;
        uint32_t a = addr + done;
        if ((r = read_chunk(io, a, buf, len)))
            break;
        for (uint32_t i = 0; i < len; i++)
            if (buf[i] != data[done + i]) {
                if (bad_addr)
                    *bad_addr = a + i;
                return fail(io, -EIO, "verification failed at 0x%06X (file: 0x%02X, "
                                      "flash: 0x%02X)", a + i, data[done + i], buf[i]);
            }
        progress(io, "Verifying", done + len, n);
    }
    return r;
}

/* Spartan-6 configuration packets, byte for byte what mesaflash writes
 * (recorded in tests/data/eth/mesaflash/7i92-bootblock.hex): padding, sync
 * word, GENERAL1/2 = the MultiBoot (user) address 0x100000 with read opcode
 * 0x0B, GENERAL3/4 = the fallback address 0x010000, CMD = IPROG, NOOPs. */
static const uint8_t boot_block[] = {
    0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xAA, 0x99, 0x55,
    0x66, 0x31, 0xE1, 0xFF, 0xFF, 0x32, 0x61, 0x00, 0x00, 0x32, 0x81, 0x0B, 0x10,
    0x32, 0xA1, 0x00, 0x00, 0x32, 0xC1, 0x0B, 0x01, 0x30, 0xA1, 0x00, 0x00, 0x33,
    0x01, 0x21, 0x00, 0x32, 0x01, 0x00, 0x1F, 0x30, 0xA1, 0x00, 0x0E, 0x20, 0x00,
    0x20, 0x00, 0x20, 0x00, 0x20, 0x00, 0x20, 0x00, 0x20, 0x00, 0x20, 0x00};

const uint8_t *hm2_flash_boot_block(size_t *len)
{
    *len = sizeof(boot_block);
    return boot_block;
}

int hm2_flash_boot_block_ok(struct hm2_flash_io *io, int *ok)
{
    uint8_t buf[sizeof(boot_block)];
    int r = hm2_flash_read(io, HM2_FLASH_BOOT_ADDR, buf, sizeof(buf));
    if (r)
        return r;
    *ok = memcmp(buf, boot_block, sizeof(buf)) == 0;
    return 0;
}

size_t hm2_flash_iprog_words(int fallback, uint16_t *out, size_t max)
{
    uint32_t a = fallback ? HM2_FLASH_FALLBACK_ADDR : HM2_FLASH_BOOT_ADDR;
    const uint16_t seq[] = {0xFFFF, 0xFFFF, 0xAA99, 0x5566, 0x3261, (uint16_t)a, 0x3281,
                            (uint16_t)(0x0B00u | (a >> 16)), 0x30A1, 0x000E, 0x2000, 0x2000,
                            0x2000, 0x2000};
    size_t n = sizeof(seq) / sizeof(seq[0]);
    if (n > max)
        return 0;
    memcpy(out, seq, sizeof(seq));
    return n;
}

int hm2_flash_reload(struct hm2_flash_io *io, int fallback)
{
    if (io->ops)
        return io->ops->reload(io, fallback);
    uint32_t cookie = 0;
    int r = io->llio->read(io->llio, HM2_FLASH_REG_ICAP, &cookie, sizeof(cookie));
    if (r)
        return fail(io, r, "%s: read of the ICAP register failed (%s)", io->llio->name,
                    strerror(-r));
    if (cookie != HM2_FLASH_ICAP_COOKIE)
        return fail(io, -ENOTSUP, "%s: Active firmware too old to support --reload (ICAP "
                                  "register 0x%08X, not 0x%08X): power cycle the board",
                    io->llio->name, cookie, HM2_FLASH_ICAP_COOKIE);
    uint16_t seq[16];
    size_t n = hm2_flash_iprog_words(fallback, seq, 16);
    for (size_t i = 0; i < n; i++) {
        if ((r = reg_write(io, HM2_FLASH_REG_ICAP, seq[i])))
            return r;
        io->delay_ns(io->delay_ctx, 1000000ull); /* 1 ms between words, as mesaflash */
    }
    return 0;
}

int hm2_flash_boot_status(struct hm2_flash_io *io, uint32_t *bootsts)
{
    if (io->ops)
        return fail(io, -ENOTSUP, "%s: no boot status through this interface", io->llio->name);
    int r = io->llio->read(io->llio, HM2_FLASH_REG_BOOTSTS, bootsts, sizeof(*bootsts));
    if (r)
        return fail(io, r, "%s: read of the boot status failed (%s)", io->llio->name,
                    strerror(-r));
    return 0;
}
