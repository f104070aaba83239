/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hmid.c - the firmware listing of a probed board in mesaflash's
 * --readhmid layout (hm2/hmid.h): IDROM header, module descriptors and the
 * pin-out with mesaflash's module and pin-function names.  The layout and
 * names were recorded from Debian's mesaflash against the virtual 7i92 and
 * 7i96S (tests/flash/data/mesaflash-*-readhmid.txt).  No HAL calls.
 */
#define _POSIX_C_SOURCE 200809L
#include "hm2/hmid.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* mesaflash's module names where they differ from the driver's. */
static const char *module_name(int gtag, char *buf, size_t len)
{
    switch (gtag) {
    case HM2_GTAG_WATCHDOG: return "WatchDog";
    case HM2_GTAG_ENCODER: return "QCount";
    case HM2_GTAG_PWMGEN: return "PWM";
    case HM2_GTAG_MUXED_ENCODER: return "MuxedQCount";
    case HM2_GTAG_MUXED_ENCODER_SEL: return "MuxedQCountSel";
    case HM2_GTAG_SMARTSERIAL: return "SSerial";
    case HM2_GTAG_LED: return "LED";
    default: return hm2_gtag_name(gtag, buf, len);
    }
}

/* mesaflash's name of a pin's secondary function; NULL = use the driver's. */
static const char *pin_function(const struct hm2_pin *p, char *buf, size_t len)
{
    static const char *const stepgen[] = {"Step/Table1", "Dir/Table2", "Table3", "Table4",
                                          "Table5",      "Table6",     "Table7", "Table8"};
    static const char *const qcount[] = {"Quad-A", "Quad-B", "Quad-IDX", "Quad-IDXM",
                                         "Quad-Probe"};
    static const char *const pwm[] = {"PWM", "Dir", "/Enable"};
    unsigned n = p->sec_pin & 0x7Fu;
    switch (p->sec_tag) {
    case HM2_GTAG_STEPGEN:
        return n >= 1 && n <= 8 ? stepgen[n - 1] : NULL;
    case HM2_GTAG_ENCODER:
        return n >= 1 && n <= 5 ? qcount[n - 1] : NULL;
    case HM2_GTAG_PWMGEN:
        return n >= 1 && n <= 3 ? pwm[n - 1] : NULL;
    case HM2_GTAG_SMARTSERIAL:
        if (p->sec_pin >= 0x01 && p->sec_pin <= 0x08)
            snprintf(buf, len, "RXData%u", p->sec_pin - 0x01u);
        else if (p->sec_pin >= 0x81 && p->sec_pin <= 0x88)
            snprintf(buf, len, "TXData%u", p->sec_pin - 0x81u);
        else if (p->sec_pin >= 0x91 && p->sec_pin <= 0x98)
            snprintf(buf, len, "TXEn%u", p->sec_pin - 0x91u);
        else
            return NULL;
        return buf;
    default:
        return NULL;
    }
}

static void print_header(const hostmot2_t *hm2, FILE *f)
{
    const struct hm2_idrom *id = &hm2->idrom;
    fprintf(f, "Configuration Name: HOSTMOT2\n\n");
    fprintf(f, "General configuration information:\n\n");
    fprintf(f, "  BoardName : %.8s\n", id->board_name);
    fprintf(f, "  FPGA Size: %u KGates\n", id->fpga_size);
    fprintf(f, "  FPGA Pins: %u\n", id->fpga_pins);
    fprintf(f, "  Number of IO Ports: %u\n", id->io_ports);
    fprintf(f, "  Width of one I/O port: %u\n", id->port_width);
    fprintf(f, "  Clock Low frequency: %.4f MHz\n", id->clock_low / 1e6);
    fprintf(f, "  Clock High frequency: %.4f MHz\n", id->clock_high / 1e6);
    fprintf(f, "  IDROM Type: %u\n", id->idrom_type);
    fprintf(f, "  Instance Stride 0: %u\n", id->instance_stride_0);
    fprintf(f, "  Instance Stride 1: %u\n", id->instance_stride_1);
    fprintf(f, "  Register Stride 0: %u\n", id->register_stride_0);
    fprintf(f, "  Register Stride 1: %u\n\n", id->register_stride_1);
}

static void print_modules(const hostmot2_t *hm2, FILE *f)
{
    fprintf(f, "Modules in configuration:\n\n");
    for (int i = 0; i < hm2->num_mds; i++) {
        const struct hm2_md *md = &hm2->md[i];
        char unk[32];
        const char *n = module_name(md->gtag, unk, sizeof(unk));
        fprintf(f, "  Module: %s\n", n);
        fprintf(f, "  There are %u of %s in configuration\n", md->instances, n);
        fprintf(f, "  Version: %u\n", md->version);
        fprintf(f, "  Registers: %u\n", md->num_registers);
        fprintf(f, "  BaseAddress: %04X\n", md->base_address);
        fprintf(f, "  ClockFrequency: %.3f MHz\n", md->clock_freq / 1e6);
        fprintf(f, "  Register Stride: %u bytes\n", md->register_stride);
        fprintf(f, "  Instance Stride: %u bytes\n\n", md->instance_stride);
    }
}

/* Boards whose I/O connectors mesaflash lists by DB25 pin number (recorded:
 * the 7i92's P1 and P2). */
static int db25_board(const hostmot2_t *hm2)
{
    static const char *const boards[] = {"7i92"};
    const char *n = hm2->llio->name;
    if (strncmp(n, "hm2_", 4) != 0)
        return 0;
    n += 4;
    size_t len = strcspn(n, ".");
    for (size_t i = 0; i < sizeof(boards) / sizeof(boards[0]); i++)
        if (strlen(boards[i]) == len && strncmp(n, boards[i], len) == 0)
            return 1;
    return 0;
}

static void print_pin(const hostmot2_t *hm2, int i, int db25, FILE *f)
{
    const struct hm2_pin *p = &hm2->pin[i];
    char cbuf[64], mbuf[32], fbuf[32];
    const char *label = hm2_llio_pin_name(hm2->llio, i, cbuf, sizeof(cbuf));
    const char *dash = label ? strrchr(label, '-') : NULL;
    if (db25 && dash)
        fprintf(f, "%2u                ", (unsigned)strtoul(dash + 1, NULL, 10));
    else
        fprintf(f, "%-18s", label ? label : "?");
    fprintf(f, "    %3d   %-8s", i, "IOPort");
    if (p->sec_tag == 0) {
        fprintf(f, "     %-15s\n", "None");
        return;
    }
    fprintf(f, "     %-15s", module_name(p->sec_tag, mbuf, sizeof(mbuf)));
    if (p->sec_unit & 0x80)
        fprintf(f, " Global    ");
    else
        fprintf(f, " %2u        ", p->sec_unit);
    const char *fn = pin_function(p, fbuf, sizeof(fbuf));
    if (!fn) {
        struct hm2_pin copy = *p;
        copy.unused = false;
        fn = hm2_get_pin_secondary_name(&copy, fbuf, sizeof(fbuf));
    }
    fprintf(f, "%-12s%s\n", fn, (p->sec_pin & 0x80) ? "    (Out)" : "    (In)");
}

void hm2_print_hmid(const hostmot2_t *hm2, FILE *f)
{
    print_header(hm2, f);
    print_modules(hm2, f);
    fprintf(f, "Configuration pin-out:\n");
    int width = (int)hm2->idrom.port_width;
    int db25 = db25_board(hm2);
    for (int port = 0; port < (int)hm2->idrom.io_ports; port++) {
        const char *conn = port < HM2_LLIO_MAX_CONNECTORS ? hm2->llio->ioport_connector_name[port]
                                                     : NULL;
        fprintf(f, "\nIO Connections for %s\n", conn ? conn : "??");
        fprintf(f, "%-22sI/O   Pri. func    Sec. func        Chan     "
                   "Sec. Pin func   Sec. Pin Dir\n\n", db25 ? "DB25 pin#" : "Pin#");
        for (int b = 0; b < width; b++)
            print_pin(hm2, port * width + b, db25, f);
    }
    fprintf(f, "\n");
}
