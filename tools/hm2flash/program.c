/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * program.c - hm2flash --program: load a firmware into the FPGA itself
 * (volatile: gone at the next power-up), with the method the board has:
 *
 *   PCI boards with a PLX bridge (5i20, 4i65, 5i22, 5i23, 4i68, 3x20) and
 *   their virtual boards: the bridge's configuration port (llio reset and
 *   program_fpga of the hm2_sim backend, sim:SOCKET);
 *   7i43: the CPLD's SelectMAP port over EPP (any epp_port: sim:SOCKET,
 *   ppdev:/dev/parport0, raw:0x378, gpiod:...);
 *   Pluto-P (pluto): the EP1K10's passive serial configuration over EPP
 *   control lines (an .rbf file), then a probe of the running firmware.
 *
 * Flash-configured boards (5i25, 6i25) are configured through JTAG
 * (--jtag, jtag_cmd.c), or written with --write and --reload.
 */
#define _GNU_SOURCE
#include "program.h"

#include <limits.h>

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>

#include "hm2/bitfile.h"
#include "hm2/boards.h"
#include "hm2/epp_port.h"
#include "hm2_7i43_llio.h"
#include "hm2_sim_llio.h"
#include "pluto_common.h"
#include "source_pci.h"

#define BIT_MAX (16u << 20)

static uint64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

static void done_line(uint32_t bytes, uint64_t t0)
{
    printf("  Programming [########################################] 100%% %u bytes in %.2f s\n",
           bytes, (double)(mono_ns() - t0) / 1e9);
}

/* ---- logging of the backends: errors to stderr ---- */

static void hm2_log(void *ctx, int level, const char *line)
{
    (void)ctx;
    if (level == HM2_ERR)
        fprintf(stderr, "hm2flash: %s\n", line);
}

static void h7_log(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void h7_log(int level, const char *fmt, ...)
{
    if (level != H7_ERR && level != H7_PRINT)
        return;
    va_list ap;
    va_start(ap, fmt);
    fputs("hm2flash: ", stderr);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
}

static long long h7_now(void)
{
    return (long long)mono_ns();
}

static void pluto_log(void *ctx, int level, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void pluto_log(void *ctx, int level, const char *fmt, ...)
{
    (void)ctx;
    if (level != PLUTO_ERR)
        return;
    va_list ap;
    va_start(ap, fmt);
    fputs("hm2flash: ", stderr);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
}

/* ---- .BIT for hm2 boards ---- */

static int part_possible(const struct hm2_board_info *board, const char *part);

static int load_bit(const char *path, const struct hm2_board_info *board, uint8_t **buf,
                    struct hm2_bitfile *bf)
{
    size_t len = 0;
    int r = hm2_read_file(path, BIT_MAX, buf, &len);
    if (r) {
        fprintf(stderr, "hm2flash: cannot read %s: %s\n", path,
                r == -EFBIG ? "not a regular file or too large" : strerror(-r));
        return r;
    }
    char err[160];
    r = hm2_bitfile_parse(*buf, len, bf, err, sizeof(err));
    printf("Checking file... %s\n", r ? "" : "OK");
    if (r) {
        fprintf(stderr, "hm2flash: %s: %s\n", path, err);
        goto bad;
    }
    if (!part_possible(board, bf->part)) {
        fprintf(stderr, "hm2flash: Error: %s: wrong bitfile destination device: %s, should be "
                        "%s; the FPGA was not touched\n", path, bf->part, board->fpga_part);
        r = -EINVAL;
        goto bad;
    }
    return 0;
bad:
    free(*buf);
    *buf = NULL;
    return r;
}

/* A 7i43 reports its FPGA size only after its CPLD reset the FPGA: before
 * that the file may name either part. */
static int part_possible(const struct hm2_board_info *board, const char *part)
{
    if (strcasecmp(board->name, "7i43") == 0)
        return strcasecmp(part, "3s400tq144") == 0 || strcasecmp(part, "3s200tq144") == 0;
    return strcasecmp(part, board->fpga_part) == 0;
}

/* reset + program_fpga of any llio that has them */
static int program_llio(hm2_llio_t *llio, const struct hm2_bitfile *bf, const char *path,
                        const char *method)
{
    if (strcasecmp(bf->part, llio->fpga_part_number) != 0) {
        fprintf(stderr, "hm2flash: Error: %s: wrong bitfile destination device: %s, the board "
                        "has a %s; the FPGA stays unconfigured\n", path, bf->part,
                llio->fpga_part_number);
        return 1;
    }
    printf("Programming FPGA (%s)...\n", method);
    uint64_t t0 = mono_ns();
    int r = llio->reset(llio);
    if (!r)
        r = llio->program_fpga(llio, bf);
    if (r) {
        fprintf(stderr, "hm2flash: Error: programming the FPGA of %s failed\n", llio->name);
        return 1;
    }
    done_line(bf->size, t0);
    return 0;
}

static int program_pci(const struct program_req *q, uint8_t *buf, const struct hm2_bitfile *bf)
{
    char model[16], why[300];
    snprintf(model, sizeof(model), "%s", q->board->name);
    char *dash = strchr(model, '-');
    if (dash)
        *dash = 0;
    hm2_llio_t *llio = NULL;
    void *h = NULL;
    int rc = 1;
    if (hm2flash_open_pci(q->addr + 4, model, &llio, &h, why, sizeof(why)))
        fprintf(stderr, "hm2flash: %s\n", why);
    else
        rc = program_llio(llio, bf, q->file, "PCI bridge configuration port");
    if (!rc)
        printf("Board configured: DONE high\n");
    hm2flash_close_pci(h);
    free(buf);
    return rc;
}

static int program_localbus(const struct program_req *q)
{
    int pci = q->addr && strncmp(q->addr, "pci:", 4) == 0;
    if (!pci && (!q->addr || strncmp(q->addr, "sim:", 4) != 0)) {
        fprintf(stderr, "hm2flash: --addr %s: want sim:SOCKET or pci:[ADDR] for a %s\n",
                q->addr ? q->addr : "(none)", q->board->name);
        return 1;
    }
    uint8_t *buf = NULL;
    struct hm2_bitfile bf;
    if (load_bit(q->file, q->board, &buf, &bf))
        return 1;
    if (pci)
        return program_pci(q, buf, &bf);
    struct hm2_sim_board *sb = calloc(1, sizeof(*sb));
    if (!sb || hm2_sim_setup(sb, q->addr + 4, q->board->name, 0, NULL, hm2_log, NULL)) {
        free(sb);
        free(buf);
        return 1;
    }
    int rc = program_llio(&sb->llio, &bf, q->file, "PCI bridge configuration port");
    free(buf);
    if (!rc) {
        struct vb_hello h;
        if (vbc_hello(&sb->vbc, &h) == 0)
            printf("Board configured: firmware %.32s (DONE high)\n", h.firmware);
    }
    hm2_sim_teardown(sb);
    free(sb);
    return rc;
}

static int program_7i43(const struct program_req *q)
{
    epp_port_t port;
    char err[256];
    uint8_t *buf = NULL;
    struct hm2_bitfile bf;
    if (load_bit(q->file, q->board, &buf, &bf))
        return 1;
    if (epp_port_open(&port, q->addr ? q->addr : "", 0, 0, 1, err, sizeof(err))) {
        fprintf(stderr, "hm2flash: %s\n", err);
        free(buf);
        return 1;
    }
    struct hm2_7i43 *b = calloc(1, sizeof(*b));
    int rc = 1;
    if (!b || hm2_7i43_setup_board(b, &port, 0, 1, 0, h7_log, h7_now))
        goto out;
    rc = program_llio(&b->llio, &bf, q->file, "7i43 CPLD over EPP");
    if (!rc) {
        uint32_t cookie = 0;
        if (b->llio.read(&b->llio, 0x100, &cookie, 4) == 0 && cookie == 0x55AACAFEu)
            printf("Board configured: hm2 firmware answers (cookie 0x%08X)\n", cookie);
        else {
            fprintf(stderr, "hm2flash: the 7i43 does not answer after programming (cookie "
                            "0x%08X)\n", cookie);
            rc = 1;
        }
    }
out:
    free(b);
    free(buf);
    epp_port_close(&port);
    return rc;
}

static int program_pluto(const struct program_req *q)
{
    epp_port_t port;
    char err[256], path[512];
    uint8_t *img = NULL;
    size_t len = 0;
    /* a file named on the command line is taken as it is; a bare name that
     * is no file here is looked up on the firmware path, as the drivers do */
    char *abs = realpath(q->file, NULL);
    int r = pluto_read_firmware(abs ? abs : q->file, &img, &len, path, sizeof(path), err,
                                sizeof(err));
    free(abs);
    if (r) {
        fprintf(stderr, "hm2flash: %s\n", err);
        return 1;
    }
    printf("Checking file... OK\n  File type: Altera raw binary (.rbf), %zu bytes\n", len);
    if (epp_port_open(&port, q->addr ? q->addr : "", 0, 0, 0, err, sizeof(err))) {
        fprintf(stderr, "hm2flash: %s\n", err);
        free(img);
        return 1;
    }
    struct pluto_log log = {pluto_log, NULL};
    printf("Programming FPGA (Pluto-P passive serial over EPP)...\n");
    uint64_t t0 = mono_ns();
    int rc = 1;
    if (pluto_upload(&port, img, len, &log))
        goto out;
    done_line(len < PLUTO_UPLOAD_BYTES ? (uint32_t)len : PLUTO_UPLOAD_BYTES, t0);
    if (pluto_probe(&port, "pluto", &log))
        goto out;
    printf("Board configured: the Pluto-P answers\n");
    rc = 0;
out:
    free(img);
    epp_port_close(&port);
    return rc;
}

int hm2flash_program(const struct program_req *q)
{
    if (!q->board)
        return program_pluto(q);
    if (!q->board->programmable) {
        fprintf(stderr, "hm2flash: the %s configures itself from its flash: volatile "
                        "programming needs JTAG (--jtag CABLE --program FILE); or --write FILE "
                        "then --reload\n", q->board->name);
        return 1;
    }
    if (strncasecmp(q->board->name, "7i43", 4) == 0)
        return program_7i43(q);
    return program_localbus(q);
}
