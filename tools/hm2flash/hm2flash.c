/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2flash - write, verify, back up and reload the configuration flash of a
 * Mesa-style board (mesaflash's command set); see docs/hm2flash.md.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include "flash_image.h"
#include "hm2/bitfile.h"
#include "hm2/boards.h"
#include "hm2/cfgflash.h"
#include "hm2/hm2.h"
#include "hm2/hmid.h"
#include "hm2flash.h"
#include "jtag_cmd.h"
#include "program.h"

#define BIT_MAX (16u << 20)

enum cmd {
    CMD_INFO_BOARD,
    CMD_WRITE,
    CMD_VERIFY,
    CMD_BACKUP,
    CMD_RELOAD,
    CMD_INFO_FILE,
    CMD_PROGRAM,
    CMD_SCAN,
    CMD_READHMID
};

struct opts {
    const char *device, *addr, *file, *jtag;
    enum cmd cmd;
    int ncmds;
    int fallback, fix_boot, no_verify, verbose;
};

static void usage(FILE *f)
{
    fprintf(f,
            "Syntax:\n"
            "  hm2flash --device NAME --addr SOURCE [options]\n"
            "  hm2flash --device NAME --addr SOURCE [options] --write FILE.bit\n"
            "  hm2flash --device NAME --addr SOURCE [options] --verify FILE.bit\n"
            "  hm2flash --device NAME --addr SOURCE [options] --backup-flash FILE\n"
            "  hm2flash --device NAME --addr SOURCE [options] --reload\n"
            "  hm2flash --device NAME --addr SOURCE --readhmid\n"
            "  hm2flash --device NAME --addr SOURCE --program FILE (.BIT; .rbf for pluto)\n"
            "  hm2flash --jtag CABLE --scan\n"
            "  hm2flash --jtag CABLE --program FILE.bit\n"
            "  hm2flash --info FILE.bit\n"
            "  hm2flash --help\n"
            "SOURCE: pci:[ADDR] (a Mesa PCI board, the default), sim:SOCKET (a virtual\n"
            "        board, bin/vboard --socket SOCKET); for the Ethernet boards (7i92,\n"
            "        7i96s) the IP address (default 192.168.1.121); for the\n"
            "        EPP boards (7i43, pluto) any EPP port: ppdev:/dev/parport0, raw:0x378, ...\n"
            "CABLE: ftdi (0403:6010), ftdi:VID:PID or ftdi:VID:PID:SERIAL (FTDI MPSSE),\n"
            "       gpiod:CHIP:TCK/TMS/TDI/TDO (GPIO lines, e.g. gpiod:gpiochip0:11/25/10/9)\n"
            "Options:\n"
            "  --fallback          use the fallback area of the flash\n"
            "  --fix-boot-block    write a boot block when --write finds none\n"
            "  --no-auto-verify    do not verify after --write\n"
            "  --verbose           more detail\n");
}

static int set_cmd(struct opts *o, enum cmd c, const char *file)
{
    o->cmd = c;
    o->file = file;
    return ++o->ncmds;
}

static int parse(int argc, char **argv, struct opts *o)
{
    static const struct option lo[] = {
        {"device", required_argument, 0, 'd'}, {"addr", required_argument, 0, 'a'},
        {"write", required_argument, 0, 'w'},  {"verify", required_argument, 0, 'V'},
        {"backup-flash", required_argument, 0, 'b'}, {"reload", no_argument, 0, 'r'},
        {"info", required_argument, 0, 'i'},   {"fallback", no_argument, 0, 'f'},
        {"fix-boot-block", no_argument, 0, 'x'}, {"no-auto-verify", no_argument, 0, 'n'},
        {"verbose", no_argument, 0, 'v'},      {"help", no_argument, 0, 'h'},
        {"program", required_argument, 0, 'p'}, {"jtag", required_argument, 0, 'j'},
        {"scan", no_argument, 0, 's'},         {"readhmid", no_argument, 0, 'R'},
        {0, 0, 0, 0}};
    memset(o, 0, sizeof(*o));
    o->cmd = CMD_INFO_BOARD;
    int c;
    while ((c = getopt_long(argc, argv, "", lo, NULL)) != -1) {
        switch (c) {
        case 'd': o->device = optarg; break;
        case 'a': o->addr = optarg; break;
        case 'w': set_cmd(o, CMD_WRITE, optarg); break;
        case 'V': set_cmd(o, CMD_VERIFY, optarg); break;
        case 'b': set_cmd(o, CMD_BACKUP, optarg); break;
        case 'r': set_cmd(o, CMD_RELOAD, NULL); break;
        case 'i': set_cmd(o, CMD_INFO_FILE, optarg); break;
        case 'p': set_cmd(o, CMD_PROGRAM, optarg); break;
        case 'j': o->jtag = optarg; break;
        case 's': set_cmd(o, CMD_SCAN, NULL); break;
        case 'R': set_cmd(o, CMD_READHMID, NULL); break;
        case 'f': o->fallback = 1; break;
        case 'x': o->fix_boot = 1; break;
        case 'n': o->no_verify = 1; break;
        case 'v': o->verbose = 1; break;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
    }
    if (optind < argc) {
        fprintf(stderr, "hm2flash: unexpected argument '%s'\n", argv[optind]);
        return 2;
    }
    if (o->ncmds > 1) {
        fprintf(stderr, "hm2flash: give one command (--write, --verify, --backup-flash, "
                        "--reload, --readhmid, --program, --info)\n");
        return 2;
    }
    if (o->jtag && o->cmd != CMD_SCAN && o->cmd != CMD_PROGRAM) {
        fprintf(stderr, "hm2flash: --jtag goes with --scan or --program FILE\n");
        return 2;
    }
    if (o->cmd == CMD_SCAN && !o->jtag) {
        fprintf(stderr, "hm2flash: --scan needs --jtag CABLE\n");
        return 2;
    }
    if (o->cmd != CMD_INFO_FILE && !o->jtag && !o->device) {
        fprintf(stderr, "hm2flash: --device NAME is required (e.g. --device 5i25)\n");
        return 2;
    }
    return -1;
}

/* ---- .BIT files ---- */

struct bitfile {
    uint8_t *buf;
    size_t len;
    struct hm2_bitfile bf;
};

static int load_bitfile(const char *path, struct bitfile *b)
{
    memset(b, 0, sizeof(*b));
    int r = hm2_read_file(path, BIT_MAX, &b->buf, &b->len);
    if (r) {
        printf("Checking file... \n");
        fprintf(stderr, "hm2flash: cannot read %s: %s\n", path,
                r == -EFBIG ? "not a regular file or too large" : strerror(-r));
        return r;
    }
    char err[160];
    r = hm2_bitfile_parse(b->buf, b->len, &b->bf, err, sizeof(err));
    printf("Checking file... %s\n", r ? "" : "OK");
    if (r) {
        fprintf(stderr, "hm2flash: %s: %s\n", path, err);
        free(b->buf);
        b->buf = NULL;
    }
    return r;
}

static void print_bitfile(const struct bitfile *b)
{
    printf("  File type: Xilinx bit file\n");
    printf("  Design name: %s\n", b->bf.design ? b->bf.design : "");
    printf("  Part name: %s\n", b->bf.part);
    printf("  Design date: %s\n", b->bf.date ? b->bf.date : "");
    printf("  Design time: %s\n", b->bf.time ? b->bf.time : "");
    printf("  Config Length: %u\n", b->bf.size);
}

static int cmd_info_file(const struct opts *o)
{
    struct bitfile b;
    if (load_bitfile(o->file, &b))
        return 1;
    print_bitfile(&b);
    free(b.buf);
    return 0;
}

/* ---- board commands ---- */

static uint32_t area_addr(const struct hm2flash_board *bd, const struct opts *o)
{
    return o->fallback ? bd->fallback_addr : bd->user_addr;
}

static uint32_t area_size(const struct hm2flash_board *bd, const struct opts *o)
{
    uint32_t end = bd->io.size < bd->user_addr ? bd->io.size : bd->user_addr;
    if (o->fallback)
        return end > bd->fallback_addr ? end - bd->fallback_addr : 0;
    return bd->io.size > bd->user_addr ? bd->io.size - bd->user_addr : 0; /* small flash: none */
}

static int check_boot_block(struct hm2flash_board *bd, const struct opts *o)
{
    int ok = 0;
    if (!bd->boot_block) /* the FPGA family boots without one */
        return 0;
    if (hm2_flash_boot_block_ok(&bd->io, &ok))
        return -1;
    if (ok) {
        printf("Boot sector OK\n");
        return 0;
    }
    if (!o->fix_boot) {
        fprintf(stderr, "hm2flash: Error: BootSector is invalid (use --fix-boot-block to write "
                        "one)\n");
        return -1;
    }
    size_t len;
    const uint8_t *bb = hm2_flash_boot_block(&len);
    printf("Writing boot block...\n");
    hm2flash_progress_begin(bd);
    int r = hm2_flash_write(&bd->io, HM2_FLASH_BOOT_ADDR, bb, (uint32_t)len);
    hm2flash_progress_end(bd);
    if (r) {
        fprintf(stderr, "hm2flash: %s\n", bd->io.err);
        return -1;
    }
    printf("Boot sector OK\n");
    return 0;
}

static int do_verify(struct hm2flash_board *bd, const struct opts *o, const struct bitfile *b)
{
    uint32_t at = area_addr(bd, o), bad = 0;
    printf("Verifying FLASH memory sectors starting from 0x%X...\n", at);
    hm2flash_progress_begin(bd);
    int r = hm2_flash_verify(&bd->io, at, b->bf.data, b->bf.size, &bad);
    hm2flash_progress_end(bd);
    if (r) {
        fprintf(stderr, "hm2flash: Error: %s\n", bd->io.err);
        return 1;
    }
    printf("Board FLASH memory verified successfully.\n");
    return 0;
}

static int load_checked(struct hm2flash_board *bd, const struct opts *o, struct bitfile *b)
{
    if (load_bitfile(o->file, b))
        return -1;
    struct flash_image_info info;
    char err[200];
    if (flash_image_check(&b->bf, bd->board->name, bd->board->fpga_part, area_size(bd, o),
                          &info, err, sizeof(err))) {
        fprintf(stderr, "hm2flash: Error: %s: %s; nothing written\n", o->file, err);
        free(b->buf);
        b->buf = NULL;
        return -1;
    }
    printf("  File type: Xilinx bit file\n");
    return 0;
}

static int cmd_write(struct hm2flash_board *bd, const struct opts *o)
{
    struct bitfile b;
    if (load_checked(bd, o, &b))
        return 1;
    int rc = 1;
    if (!o->fallback && check_boot_block(bd, o))
        goto out;
    if (o->fallback && check_boot_block(bd, &(struct opts){.fix_boot = 1}))
        goto out;
    uint32_t at = area_addr(bd, o);
    printf("FLASH memory sectors to write: %u, max sectors in area: %u\n",
           (b.bf.size + HM2_FLASH_SECTOR - 1) / HM2_FLASH_SECTOR,
           area_size(bd, o) / HM2_FLASH_SECTOR);
    bd->area_addr = at;
    printf("Erasing FLASH memory sectors starting from 0x%X...\n", at);
    hm2flash_progress_begin(bd);
    int r = hm2_flash_write(&bd->io, at, b.bf.data, b.bf.size);
    hm2flash_progress_end(bd);
    if (r) {
        fprintf(stderr, "hm2flash: Error: %s\n", bd->io.err);
        goto out;
    }
    printf("Board configuration updated successfully.\n");
    rc = o->no_verify ? 0 : do_verify(bd, o, &b);
    if (!rc)
        printf("\nYou must power cycle the hardware or use the --reload command to load a new "
               "firmware.\n");
out:
    free(b.buf);
    return rc;
}

static int cmd_verify(struct hm2flash_board *bd, const struct opts *o)
{
    struct bitfile b;
    if (load_checked(bd, o, &b))
        return 1;
    int rc = do_verify(bd, o, &b);
    free(b.buf);
    return rc;
}

static int cmd_backup(struct hm2flash_board *bd, const struct opts *o)
{
    uint8_t *buf = malloc(bd->io.size);
    if (!buf) {
        fprintf(stderr, "hm2flash: out of memory\n");
        return 1;
    }
    int rc = 1;
    printf("Reading all FLASH memory (%u bytes)...\n", bd->io.size);
    hm2flash_progress_begin(bd);
    int r = hm2_flash_read(&bd->io, 0, buf, bd->io.size);
    hm2flash_progress_end(bd);
    if (r) {
        fprintf(stderr, "hm2flash: Error: %s\n", bd->io.err);
        goto out;
    }
    FILE *f = fopen(o->file, "wb");
    if (!f || fwrite(buf, 1, bd->io.size, f) != bd->io.size || fclose(f) != 0) {
        fprintf(stderr, "hm2flash: cannot write %s: %s\n", o->file, strerror(errno));
        goto out;
    }
    printf("Flash memory backed up to %s\n", o->file);
    rc = 0;
out:
    free(buf);
    return rc;
}

static void print_bootsts(struct hm2flash_board *bd)
{
    uint32_t s = 0;
    if (bd->is_pci) /* Mesa's firmware has no boot status register */
        return;
    if (hm2_flash_boot_status(&bd->io, &s))
        return;
    printf("  Boot status: 0x%02X%s%s%s%s%s\n", s, s & HM2_BOOTSTS_VALID ? " valid" : "",
           s & HM2_BOOTSTS_FALLBACK ? " fallback-used" : "",
           s & HM2_BOOTSTS_IPROG ? " reloaded" : "",
           s & HM2_BOOTSTS_ID_ERROR ? " id-error" : "",
           s & HM2_BOOTSTS_CRC_ERROR ? " crc-error" : "");
    if (s & HM2_BOOTSTS_FALLBACK)
        printf("  Warning: the board runs its FALLBACK image: the user image is %s; write it "
               "again (--write) and --reload\n",
               s & HM2_BOOTSTS_ID_ERROR ? "for another board" : "corrupt or missing");
}

static int cmd_reload(struct hm2flash_board *bd, const struct opts *o)
{
    if (hm2_flash_reload(&bd->io, o->fallback)) {
        fprintf(stderr, "hm2flash: Error: %s\n", bd->io.err);
        return 1;
    }
    int r = hm2flash_reopen(bd);
    if (r) {
        fprintf(stderr, "hm2flash: the FPGA did not come back after the reload: %s\n",
                bd->why);
        return 1;
    }
    printf("Board reloaded from the %s image: firmware %s\n",
           o->fallback ? "fallback" : "flash", bd->firmware);
    print_bootsts(bd);
    return 0;
}

static void quiet_log(void *ctx, int level, const char *line)
{
    (void)ctx;
    if (level == HM2_ERR)
        fprintf(stderr, "hm2flash: %s\n", line);
}

/* The firmware's IDROM, modules and pin-out, as mesaflash --readhmid
 * prints them (the listing is hm2pinout --pin-file's, hm2/hmid.h). */
static int cmd_readhmid(struct hm2flash_board *bd)
{
    hm2_llio_t *llio = bd->io.llio;
    int (*reset)(hm2_llio_t *) = llio->reset;
    int (*program)(hm2_llio_t *, const struct hm2_bitfile *) = llio->program_fpga;
    llio->reset = NULL; /* read only: never reset or load anything */
    llio->program_fpga = NULL;
    struct hm2_options ho = {{0, 0, 0, 0}, NULL};
    int err = 0;
    hostmot2_t *hm2 = hm2_probe(llio, NULL, &ho, quiet_log, NULL, &err);
    llio->reset = reset;
    llio->program_fpga = program;
    if (!hm2) {
        fprintf(stderr, "hm2flash: %s: no usable HostMot2 firmware on %s (%s)\n",
                bd->description, llio->name, strerror(-err));
        return 1;
    }
    hm2_print_hmid(hm2, stdout);
    hm2_free(hm2);
    return 0;
}

static int cmd_board_info(struct hm2flash_board *bd)
{
    uint8_t id[3] = {0, 0, 0};
    int jedec = hm2_flash_jedec(&bd->io, id) == 0;
    printf("%s\n", bd->description);
    printf("  Board: %s\n", bd->display_name);
    printf("  FPGA type: %s\n", bd->board->fpga_part);
    if (jedec)
        printf("  Flash size: %s (id: 0x%02X, JEDEC %02X %02X %02X)\n",
               hm2_flash_size_text(bd->io.signature), bd->io.signature, id[0], id[1], id[2]);
    else
        printf("  Flash size: %s (id: 0x%02X)\n", hm2_flash_size_text(bd->io.signature),
               bd->io.signature);
    printf("  Firmware: %s\n", bd->firmware);
    print_bootsts(bd);
    return 0;
}

int main(int argc, char **argv)
{
    struct opts o;
    int rc = parse(argc, argv, &o);
    if (rc >= 0)
        return rc;
    if (o.cmd == CMD_INFO_FILE)
        return cmd_info_file(&o);
    if (o.jtag)
        return o.cmd == CMD_SCAN ? hm2flash_jtag_scan(o.jtag)
                                 : hm2flash_jtag_program(o.jtag, o.file);
    if (o.cmd == CMD_PROGRAM) {
        struct program_req q = {hm2_board_lookup(o.device), o.addr, o.file};
        if (!q.board && strcasecmp(o.device, "pluto") != 0) {
            fprintf(stderr, "hm2flash: No %s board found (unknown board name)\n", o.device);
            return 1;
        }
        return hm2flash_program(&q);
    }
    struct hm2flash_board bd;
    if (hm2flash_open(&bd, o.device, o.addr)) {
        fprintf(stderr, "hm2flash: %s\n", bd.why);
        return 1;
    }
    if (hm2_flash_identify(&bd.io)) {
        fprintf(stderr, "hm2flash: %s\n", bd.io.err);
        hm2flash_close(&bd);
        return 1;
    }
    switch (o.cmd) {
    case CMD_WRITE: rc = cmd_write(&bd, &o); break;
    case CMD_VERIFY: rc = cmd_verify(&bd, &o); break;
    case CMD_BACKUP: rc = cmd_backup(&bd, &o); break;
    case CMD_RELOAD: rc = cmd_reload(&bd, &o); break;
    case CMD_READHMID: rc = cmd_readhmid(&bd); break;
    default: rc = cmd_board_info(&bd); break;
    }
    hm2flash_close(&bd);
    return rc;
}
