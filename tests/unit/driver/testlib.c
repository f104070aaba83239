/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _POSIX_C_SOURCE 200809L
#include "testlib.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/boards.h"

void tlog_sink(void *ctx, int level, const char *line)
{
    struct tlog *t = ctx;
    if (t->echo)
        fprintf(stderr, "[%d] %s\n", level, line);
    if (t->n >= TLOG_MAX_LINES)
        return;
    t->line[t->n] = strdup(line);
    t->level[t->n] = level;
    t->n++;
}

void tlog_clear(struct tlog *t)
{
    for (int i = 0; i < t->n; i++)
        free(t->line[i]);
    t->n = 0;
}

void t_squeeze(const char *in, char *out, size_t len)
{
    size_t o = 0;
    int space = 1;
    for (; *in && o + 1 < len; in++) {
        if (*in == ' ') {
            if (!space)
                out[o++] = ' ';
            space = 1;
        } else {
            out[o++] = *in;
            space = 0;
        }
    }
    while (o > 0 && out[o - 1] == ' ')
        o--;
    out[o] = '\0';
}

int tlog_find(const struct tlog *t, const char *s, int loose)
{
    char a[512], b[512];
    if (loose)
        t_squeeze(s, b, sizeof(b));
    for (int i = 0; i < t->n; i++) {
        if (loose) {
            t_squeeze(t->line[i], a, sizeof(a));
            if (strcmp(a, b) == 0)
                return i;
        } else if (strcmp(t->line[i], s) == 0) {
            return i;
        }
    }
    return -1;
}

int tlog_contains(const struct tlog *t, const char *substr)
{
    for (int i = 0; i < t->n; i++)
        if (strstr(t->line[i], substr))
            return 1;
    return 0;
}

void tlog_dump(const struct tlog *t)
{
    for (int i = 0; i < t->n; i++)
        fprintf(stderr, "  log[%d] %s\n", t->level[i], t->line[i]);
}

static char *trim(char *s)
{
    while (*s == ' ')
        s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == '\n' || s[n - 1] == '\r' || s[n - 1] == ' '))
        s[--n] = '\0';
    return s;
}

int t_csv_read(const char *path, struct t_csv *csv)
{
    FILE *f = fopen(path, "r");
    memset(csv, 0, sizeof(*csv));
    if (!f) {
        fprintf(stderr, "cannot open %s\n", path);
        return -1;
    }
    char line[1024];
    while (fgets(line, sizeof(line), f)) {
        char *l = trim(line);
        if (!*l)
            continue;
        int ncols = 1;
        for (char *p = l; *p; p++)
            ncols += *p == ',';
        char **row = calloc((size_t)ncols, sizeof(char *));
        char *save = l;
        for (int c = 0; c < ncols; c++) {
            char *comma = strchr(save, ',');
            if (comma)
                *comma = '\0';
            row[c] = strdup(trim(save));
            save = comma ? comma + 1 : save + strlen(save);
        }
        csv->cell = realloc(csv->cell, sizeof(char **) * (size_t)(csv->rows + 1));
        csv->cell[csv->rows++] = row;
        if (csv->cols == 0)
            csv->cols = ncols;
    }
    fclose(f);
    return csv->rows - 1; /* data rows */
}

void t_csv_free(struct t_csv *csv)
{
    for (int r = 0; r < csv->rows; r++) {
        for (int c = 0; c < csv->cols; c++)
            free(csv->cell[r][c]);
        free(csv->cell[r]);
    }
    free(csv->cell);
    memset(csv, 0, sizeof(*csv));
}

const char *t_csv_get(const struct t_csv *csv, int row, const char *col)
{
    for (int c = 0; c < csv->cols; c++)
        if (strcmp(csv->cell[0][c], col) == 0)
            return csv->cell[row + 1][c];
    return NULL;
}

static uint32_t chars32(const char *s)
{
    uint32_t w = 0;
    for (int i = 0; i < 4 && s[i]; i++)
        w |= (uint32_t)(uint8_t)s[i] << (8 * i);
    return w;
}

void t_build_header(struct hm2_image_llio *im, uint32_t type, uint32_t port_width,
                    uint32_t io_ports, uint32_t io_width, uint32_t clock_low, uint32_t clock_high)
{
    memset(im->mem, 0, sizeof(im->mem));
    hm2_image_put32(im, 0x100, 0x55AACAFE);
    hm2_image_put32(im, 0x104, chars32("HOST"));
    hm2_image_put32(im, 0x108, chars32("MOT2"));
    hm2_image_put32(im, 0x10C, T_IDROM);
    uint32_t h[16] = {type, T_MD_OFF, T_PD_OFF, chars32("MESA"), chars32("TEST"), 200, 208,
                      io_ports, io_width, port_width, clock_low, clock_high, 4, 64, 256, 256};
    for (int i = 0; i < 16; i++)
        hm2_image_put32(im, T_IDROM + 4u * (uint32_t)i, h[i]);
}

int t_build_image(struct hm2_image_llio *im, const struct t_firmware *fw)
{
    struct t_csv pins, mods;
    int npins = t_csv_read(fw->pins_csv, &pins);
    int nmods = t_csv_read(fw->modules_csv, &mods);
    if (npins < 0 || nmods < 0)
        return -1;
    t_build_header(im, 3, fw->port_width, fw->io_ports, (uint32_t)npins, fw->clock_low,
                   fw->clock_high);
    hm2_image_put32(im, T_IDROM + 0x0C, chars32(fw->board_name));
    hm2_image_put32(im, T_IDROM + 0x10, chars32(fw->board_name + 4));
    for (int m = 0; m < nmods; m++) {
        uint32_t gtag = (uint32_t)strtoul(t_csv_get(&mods, m, "gtag"), NULL, 0);
        uint32_t ver = (uint32_t)strtoul(t_csv_get(&mods, m, "version"), NULL, 0);
        uint32_t clk = (uint32_t)strtoul(t_csv_get(&mods, m, "clock_tag"), NULL, 0);
        uint32_t inst = (uint32_t)strtoul(t_csv_get(&mods, m, "instances"), NULL, 0);
        uint32_t base = (uint32_t)strtoul(t_csv_get(&mods, m, "base_address_hex"), NULL, 0);
        uint32_t regs = (uint32_t)strtoul(t_csv_get(&mods, m, "num_registers"), NULL, 0);
        uint32_t strides = (uint32_t)strtoul(t_csv_get(&mods, m, "strides_hex"), NULL, 0);
        uint32_t mp = (uint32_t)strtoul(t_csv_get(&mods, m, "mp_mask_hex"), NULL, 0);
        uint32_t a = T_IDROM + T_MD_OFF + 12u * (uint32_t)m;
        hm2_image_put32(im, a, inst << 24 | clk << 16 | ver << 8 | gtag);
        hm2_image_put32(im, a + 4, strides << 24 | regs << 16 | base);
        hm2_image_put32(im, a + 8, mp);
    }
    for (int p = 0; p < npins; p++) {
        uint32_t tag = (uint32_t)strtoul(t_csv_get(&pins, p, "sec_tag"), NULL, 0);
        uint32_t unit = (uint32_t)strtoul(t_csv_get(&pins, p, "sec_unit"), NULL, 0);
        uint32_t pin = (uint32_t)strtoul(t_csv_get(&pins, p, "sec_pin"), NULL, 0);
        hm2_image_put32(im, T_IDROM + T_PD_OFF + 4u * (uint32_t)p,
                        3u << 24 | unit << 16 | tag << 8 | pin);
    }
    t_csv_free(&pins);
    t_csv_free(&mods);
    return npins;
}

void t_setup_5i20(struct hm2_image_llio *im)
{
    hm2_image_llio_init(im, "hm2_5i20.0");
    hm2_image_llio_set_board(im, hm2_board_lookup("5i20"), 0);
    struct t_firmware fw = {HM2_TEST_DATA "/PIN_SVST8_4_72.csv",
                            HM2_TEST_DATA "/PIN_SVST8_4_72.modules.csv",
                            "MESA5I20",
                            33333333,
                            100000000,
                            24,
                            3};
    if (t_build_image(im, &fw) != 72)
        fprintf(stderr, "t_setup_5i20: image build failed\n");
}
