/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2pinout - print a HostMot2 board's pinout without a HAL session: the
 * same lines the hostmot2 driver logs at load (IDROM summary, module
 * instances, per-pin usage for a config string), or a .PIN-style listing
 * of the firmware.  Reads the IDROM over an llio backend; see
 * docs/hm2pinout.md.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/boards.h"
#include "hm2/hm2.h"
#include "hm2/hmid.h"
#include "hm2/llio_image.h"
#include "source_pci.h"
#include "source_sim.h"

struct opts {
    const char *board;
    int index;
    const char *config;
    int pin_file;
    int verbose;
    int no_prefix;
    const char *source;
};

static void usage(FILE *f)
{
    fprintf(f,
            "usage: hm2pinout [options] SOURCE\n"
            "  SOURCE             image:FILE or FILE: a register image (65536 bytes)\n"
            "                     or an IDROM image (1024 bytes)\n"
            "                     pci:[ADDR]: a Mesa PCI board via sysfs (first found,\n"
            "                     or e.g. pci:0000:01:00.0; -b is then ignored)\n"
            "                     sim:SOCKET: a virtual board (bin/vboard --socket SOCKET;\n"
            "                     -b is then ignored)\n"
            "  -b, --board NAME   board whose connectors to use (default 5i20); -b list\n"
            "  -n, --index N      board number in the HAL prefix (default 0)\n"
            "  -c, --config STR   hostmot2 config string (num_encoders=..., ...)\n"
            "  -p, --pin-file     print a .PIN-style listing of the firmware instead\n"
            "  -v, --verbose      also print the IDROM header and module descriptors\n"
            "  -s, --short        omit the \"hm2/<board>: \" prefix\n"
            "  -h, --help\n");
}

struct sink {
    int no_prefix;
    int show_info;
    int quiet; /* only errors and warnings */
};

static void out_sink(void *ctx, int level, const char *line)
{
    struct sink *s = ctx;
    if (level == HM2_DBG || (level == HM2_INFO && !s->show_info))
        return;
    if (s->quiet && (level == HM2_PRINT || level == HM2_INFO))
        return;
    FILE *f = (level == HM2_ERR || level == HM2_WARN) ? stderr : stdout;
    if (s->no_prefix && f == stdout) {
        const char *colon = strstr(line, ": ");
        if (colon && strncmp(line, "hm2", 3) == 0)
            line = colon + 2;
    }
    fprintf(f, "%s\n", line);
}

/* Backends reachable from this tool: each opens an llio for a SOURCE
 * string.  Only register images for now; socket/PCI/EPP backends plug in
 * here (see docs/llio.md). */
static int open_image(const char *arg, const struct hm2_board_info *b, int index,
                      struct hm2_image_llio *im)
{
    char name[32], err[256];
    snprintf(name, sizeof(name), "hm2_%s.%d", b->name, index);
    hm2_image_llio_init(im, name);
    hm2_image_llio_set_board(im, b, index);
    im->llio.program_fpga = NULL; /* never program anything */
    im->llio.reset = NULL;
    int r = hm2_image_llio_load(im, arg, err, sizeof(err));
    if (r)
        fprintf(stderr, "hm2pinout: %s\n", err);
    return r;
}

int main(int argc, char **argv)
{
    struct opts o = {"5i20", 0, NULL, 0, 0, 0, NULL};
    static const struct option lopts[] = {
        {"board", required_argument, 0, 'b'}, {"index", required_argument, 0, 'n'},
        {"config", required_argument, 0, 'c'}, {"pin-file", no_argument, 0, 'p'},
        {"verbose", no_argument, 0, 'v'},     {"short", no_argument, 0, 's'},
        {"help", no_argument, 0, 'h'},        {0, 0, 0, 0}};
    int c;
    while ((c = getopt_long(argc, argv, "b:n:c:pvsh", lopts, NULL)) != -1) {
        switch (c) {
        case 'b': o.board = optarg; break;
        case 'n': {
            char *end;
            long v = strtol(optarg, &end, 10);
            if (*end || v < 0 || v > 99) {
                fprintf(stderr, "hm2pinout: bad board index '%s' (0..99)\n", optarg);
                return 2;
            }
            o.index = (int)v;
            break;
        }
        case 'c': o.config = optarg; break;
        case 'p': o.pin_file = 1; break;
        case 'v': o.verbose = 1; break;
        case 's': o.no_prefix = 1; break;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
    }
    if (strcmp(o.board, "list") == 0) {
        for (int i = 0; hm2_board_at(i); i++) {
            const struct hm2_board_info *b = hm2_board_at(i);
            printf("%-10s %d x %d pins, FPGA %s\n", b->name, b->num_connectors,
                   b->pins_per_connector, b->fpga_part[0] ? b->fpga_part : "(flash)");
        }
        return 0;
    }
    if (optind != argc - 1) {
        usage(stderr);
        return 2;
    }
    o.source = argv[optind];
    const struct hm2_board_info *b = hm2_board_lookup(o.board);
    if (!b) {
        fprintf(stderr, "hm2pinout: unknown board '%s' (hm2pinout -b list shows them)\n", o.board);
        return 2;
    }
    const char *path = o.source;
    hm2_llio_t *llio = NULL;
    void *pci = NULL, *sim = NULL;
    struct hm2_image_llio *im = NULL;
    int rc = 1;
    if (strncmp(path, "sim:", 4) == 0) {
        if (hm2pinout_open_sim(path + 4, o.index, &llio, &sim))
            return 1;
        goto probe;
    }
    if (strncmp(path, "pci:", 4) == 0) {
        if (hm2pinout_open_pci(path + 4, o.index, &llio, &pci))
            return 1;
        goto probe;
    }
    if (strncmp(path, "image:", 6) == 0) {
        path += 6;
    } else if (strchr(path, ':') && strncmp(path, "/", 1) != 0) {
        fprintf(stderr, "hm2pinout: unknown source '%s' (image:FILE, FILE, pci:[ADDR] or sim:SOCKET)\n", o.source);
        return 2;
    }
    im = malloc(sizeof(*im));
    if (!im) {
        fprintf(stderr, "hm2pinout: out of memory\n");
        return 1;
    }
    if (open_image(path, b, o.index, im))
        goto out;
    llio = &im->llio;
probe:;
    struct sink s = {o.no_prefix, 1, o.pin_file && !o.verbose};
    struct hm2_options hopts = {{o.verbose, o.verbose, 0, 0}, NULL};
    int err;
    hostmot2_t *hm2 = hm2_probe(llio, o.config, &hopts, out_sink, &s, &err);
    if (!hm2) {
        if (pci || sim)
            fprintf(stderr, "hm2pinout: %s: no usable HostMot2 firmware on %s (%s)\n", path,
                    llio->name, strerror(-err));
        else
            fprintf(stderr, "hm2pinout: %s: not a usable HostMot2 image for a %s (%s)\n", path,
                    b->name, strerror(-err));
        goto out;
    }
    if (o.pin_file) {
        hm2_print_hmid(hm2, stdout);
    } else {
        hm2_print_modules(hm2);
        hm2_print_pin_usage(hm2);
    }
    hm2_free(hm2);
    rc = 0;
out:
    free(im);
    hm2pinout_close_pci(pci);
    hm2pinout_close_sim(sim);
    return rc;
}
