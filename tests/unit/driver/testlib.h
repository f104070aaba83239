/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * testlib.h - shared helpers of the driver unit tests: a log sink that
 * records every message line, and an IDROM image builder that works from
 * the stock pin-map CSVs (tests/data/pinmaps, the spec's pin maps) and the
 * IDROM layout of spec §3-§5, independently of the driver's own parser.
 */
#ifndef HM2_TESTLIB_H
#define HM2_TESTLIB_H

#include <stdint.h>

#include "hm2/hm2.h"
#include "hm2/llio_image.h"

#define TLOG_MAX_LINES 4096

struct tlog {
    char *line[TLOG_MAX_LINES];
    int level[TLOG_MAX_LINES];
    int n;
    int echo;
};

void tlog_sink(void *ctx, int level, const char *line);
void tlog_clear(struct tlog *t);
/* index of the first line equal to s (after collapsing runs of spaces when
 * loose), or -1 */
int tlog_find(const struct tlog *t, const char *s, int loose);
int tlog_contains(const struct tlog *t, const char *substr);
void tlog_dump(const struct tlog *t);

/* Standard type-3 IDROM layout constants (spec §3). */
#define T_IDROM 0x400u
#define T_MD_OFF 0x40u
#define T_PD_OFF 0x1C0u

struct t_firmware {
    const char *pins_csv;    /* path */
    const char *modules_csv; /* path */
    const char *board_name;  /* 8 chars, e.g. "MESA5I20" */
    uint32_t clock_low, clock_high;
    uint32_t port_width, io_ports;
};

/* Build the ID block + IDROM for a firmware from its CSVs into im->mem.
 * Returns the number of pins, or -1 (with a message on stderr). */
int t_build_image(struct hm2_image_llio *im, const struct t_firmware *fw);
/* Just the ID block and a header (no MDs/PDs) */
void t_build_header(struct hm2_image_llio *im, uint32_t type, uint32_t port_width,
                    uint32_t io_ports, uint32_t io_width, uint32_t clock_low, uint32_t clock_high);
/* 5i20 + SVST8_4 ready to probe (board table geometry). */
void t_setup_5i20(struct hm2_image_llio *im);

/* CSV reading: returns number of rows parsed into cols (strings, malloc'd;
 * free with t_csv_free). */
struct t_csv {
    int rows, cols;
    char ***cell;
};
int t_csv_read(const char *path, struct t_csv *csv);
void t_csv_free(struct t_csv *csv);
const char *t_csv_get(const struct t_csv *csv, int row, const char *col_name);

/* Collapse runs of spaces and trim (for comparing with seed printouts). */
void t_squeeze(const char *in, char *out, size_t len);

#endif
