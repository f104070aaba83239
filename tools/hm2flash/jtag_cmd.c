/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * jtag_cmd.c - hm2flash --jtag CABLE: the IDCODE scan of a JTAG chain and
 * volatile configuration of its Xilinx FPGA (JPROGRAM/CFG_IN/JSTART)
 * through an FTDI MPSSE cable over libusb or four GPIO lines (libgpiod, or
 * a virtual board's JTAG port: sim:SOCKET).
 */
#define _POSIX_C_SOURCE 200809L
#include "jtag_cmd.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/bitfile.h"
#include "hm2/jtag.h"
#include "hm2/jtag_gpio.h"
#include "hm2/jtag_mpsse.h"
#include "hm2/jtag_usb.h"
#include "hm2/jtag_xilinx.h"
#include "jtag_sim.h"

#define JTAG_HZ 6000000u
#define MAX_DEVICES 8

struct session {
    int is_gpio;
    struct jtag_gpio gpio;
    struct jtag_usb usb;
    struct mpsse m;
    struct jtag j;
    uint32_t ids[MAX_DEVICES];
    int n;
};

static void close_chain(struct session *s);

static int open_gpio(struct session *s, const char *cable)
{
    memset(s, 0, sizeof(*s));
    s->is_gpio = 1;
    struct jtag_gpio_lines lines;
    char err[256];
    int r = strncmp(cable, "sim:", 4) == 0
                ? jtag_sim_lines_open(&lines, cable + 4, err, sizeof(err))
                : jtag_gpiod_lines_open(&lines, cable + 6, err, sizeof(err));
    if (r) {
        fprintf(stderr, "hm2flash: jtag %s: %s\n", cable, err);
        return -1;
    }
    jtag_gpio_init(&s->gpio, &lines);
    struct jtag_cable c = jtag_gpio_cable(&s->gpio);
    jtag_init(&s->j, &c);
    if (jtag_scan_chain(&s->j, s->ids, MAX_DEVICES, &s->n)) {
        fprintf(stderr, "hm2flash: jtag %s: %s\n", cable, s->j.err);
        close_chain(s);
        return -1;
    }
    return 0;
}

static int open_chain(struct session *s, const char *cable)
{
    if (strncmp(cable, "gpiod:", 6) == 0 || strncmp(cable, "sim:", 4) == 0)
        return open_gpio(s, cable);
    memset(s, 0, sizeof(*s));
    if (jtag_usb_open(&s->usb, cable)) {
        fprintf(stderr, "hm2flash: jtag %s: %s\n", cable, s->usb.err);
        return -1;
    }
    struct mpsse_transport t = jtag_usb_transport(&s->usb);
    if (mpsse_open(&s->m, &t, JTAG_HZ)) {
        fprintf(stderr, "hm2flash: jtag %s: %s\n", cable, s->m.err);
        goto fail;
    }
    struct jtag_cable c = mpsse_cable(&s->m);
    jtag_init(&s->j, &c);
    if (jtag_scan_chain(&s->j, s->ids, MAX_DEVICES, &s->n)) {
        fprintf(stderr, "hm2flash: jtag %s: %s\n", cable, s->j.err);
        goto fail;
    }
    return 0;
fail:
    mpsse_close(&s->m);
    jtag_usb_close(&s->usb);
    return -1;
}

static void close_chain(struct session *s)
{
    if (s->is_gpio) {
        s->gpio.lines.close(s->gpio.lines.ctx);
        return;
    }
    mpsse_close(&s->m);
    jtag_usb_close(&s->usb);
}

static void print_chain(const struct session *s, const char *cable)
{
    printf("JTAG chain on %s (%d device%s, nearest TDO first):\n", cable, s->n,
           s->n == 1 ? "" : "s");
    for (int i = 0; i < s->n; i++) {
        const struct jtag_part *p = jtag_part_by_idcode(s->ids[i]);
        if (!s->ids[i])
            printf("  %d: no IDCODE (BYPASS at reset)\n", i);
        else
            printf("  %d: IDCODE 0x%08X %s\n", i, s->ids[i], p ? p->name : "(unknown part)");
    }
}

int hm2flash_jtag_scan(const char *cable)
{
    struct session s;
    if (open_chain(&s, cable))
        return 1;
    print_chain(&s, cable);
    close_chain(&s);
    return 0;
}

/* "XC6SLX9" fits a .BIT part "6slx9tqg144". */
static int part_fits(const struct jtag_part *p, const char *bitpart)
{
    const char *n = p->name + 2;
    size_t k = strlen(n);
    if (strlen(bitpart) < k)
        return 0;
    for (size_t i = 0; i < k; i++)
        if (tolower((unsigned char)n[i]) != tolower((unsigned char)bitpart[i]))
            return 0;
    return !isdigit((unsigned char)bitpart[k]); /* 3s400 is not 3s4000 */
}

int hm2flash_jtag_program(const char *cable, const char *file)
{
    uint8_t *buf = NULL;
    size_t len = 0;
    int r = hm2_read_file(file, 64u << 20, &buf, &len);
    if (r) {
        fprintf(stderr, "hm2flash: cannot read %s: %s\n", file, strerror(-r));
        return 1;
    }
    struct hm2_bitfile bf;
    char err[160];
    if (hm2_bitfile_parse(buf, len, &bf, err, sizeof(err))) {
        printf("Checking file... \n");
        fprintf(stderr, "hm2flash: %s: %s\n", file, err);
        free(buf);
        return 1;
    }
    printf("Checking file... OK\n");
    struct session s;
    int rc = 1;
    if (open_chain(&s, cable))
        goto out_buf;
    print_chain(&s, cable);
    int pos = -1;
    for (int i = 0; i < s.n && pos < 0; i++) {
        const struct jtag_part *p = jtag_part_by_idcode(s.ids[i]);
        if (p && part_fits(p, bf.part))
            pos = i;
    }
    if (pos < 0) {
        fprintf(stderr, "hm2flash: Error: wrong chain: %s is for a %s, no device of the chain is "
                        "one; the FPGA was not touched\n", file, bf.part);
        goto out;
    }
    printf("Programming device %d through JTAG (JPROGRAM, CFG_IN %u bytes, JSTART)...\n", pos,
           bf.size);
    uint8_t st = 0;
    if (jtag_xilinx_program(&s.j, pos, s.n, bf.data, bf.size, &st)) {
        fprintf(stderr, "hm2flash: Error: %s\n", s.j.err);
        goto out;
    }
    printf("Board configured: DONE high (IR capture 0x%02X)\n", st);
    rc = 0;
out:
    close_chain(&s);
out_buf:
    free(buf);
    return rc;
}
