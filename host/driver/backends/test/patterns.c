/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2_test register images (facts: spec §15.1 and LinuxCNC 2.9's output). */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "test_patterns.h"

#define IDROM 0x400u

static void cookie(struct hm2_image_llio *im)
{
    hm2_image_put32(im, 0x100, 0x55AACAFEu);
}

static void name_and_offset(struct hm2_image_llio *im, uint32_t offset)
{
    hm2_image_put32(im, 0x104, 0x54534F48u); /* "HOST" */
    hm2_image_put32(im, 0x108, 0x32544F4Du); /* "MOT2" */
    hm2_image_put32(im, 0x10C, offset);
}

static void header(struct hm2_image_llio *im, uint32_t type, uint32_t md_off, uint32_t pd_off,
                   uint32_t io_ports, uint32_t io_width, uint32_t port_width, uint32_t clock_low,
                   uint32_t clock_high)
{
    cookie(im);
    name_and_offset(im, IDROM);
    hm2_image_put32(im, IDROM + 0x00, type);
    hm2_image_put32(im, IDROM + 0x04, md_off);
    hm2_image_put32(im, IDROM + 0x08, pd_off);
    hm2_image_put32(im, IDROM + 0x1C, io_ports);
    hm2_image_put32(im, IDROM + 0x20, io_width);
    hm2_image_put32(im, IDROM + 0x24, port_width);
    hm2_image_put32(im, IDROM + 0x28, clock_low);
    hm2_image_put32(im, IDROM + 0x2C, clock_high);
}

int hm2_test_pattern_setup(struct hm2_image_llio *im, int pattern, int index)
{
    char name[32];
    snprintf(name, sizeof(name), "hm2_test.%d", index);
    hm2_image_llio_init(im, name);
    im->discard_writes = 1;
    im->llio.num_ioport_connectors = 1;
    im->llio.pins_per_connector = 24;
    im->llio.ioport_connector_name[0] = "P99";
    im->llio.fpga_part_number = "none";
    im->llio.num_leds = 0;
    im->llio.threadsafe = 1;

    switch (pattern) {
    case 0: break;
    case 1: cookie(im); break;
    case 2:
        cookie(im);
        name_and_offset(im, 0);
        break;
    case 3:
        cookie(im);
        name_and_offset(im, IDROM);
        hm2_image_put32(im, IDROM, 0x1234);
        break;
    case 4: header(im, 2, 0, 0, 0, 0, 0, 0, 0); break;
    case 5: header(im, 2, 0, 0, 0, 0, 29, 0, 0); break;
    case 6: header(im, 2, 0, 0, 0, 0, 24, 0, 0); break;
    case 7: header(im, 2, 0, 0, 1, 99, 24, 0, 0); break;
    case 8: header(im, 2, 0, 0, 2, 48, 24, 0, 0); break;
    case 9: header(im, 2, 0, 0, 1, 24, 24, 12345, 0); break;
    case 10: header(im, 2, 0, 0, 1, 24, 24, 2000000, 0); break;
    case 11: {
        static const char *conn[6] = {"P4", "P5", "P6", "P9", "P8", "P7"};
        header(im, 2, 0x40, 0x1C0, 6, 144, 24, 2000000, 20000000);
        im->llio.num_ioport_connectors = 6;
        for (int i = 0; i < 6; i++)
            im->llio.ioport_connector_name[i] = conn[i];
        break;
    }
    case 12:
        header(im, 2, 0x40, 0x200, 1, 24, 24, 2000000, 20000000);
        im->llio.ioport_connector_name[0] = "P3";
        for (uint32_t i = 0; i < 24; i++)
            hm2_image_put32(im, IDROM + 0x200 + 4 * i, 0x03000000u);
        break;
    case 13:
        header(im, 2, 0x40, 0x200, 1, 24, 24, 2000000, 20000000);
        im->llio.pins_per_connector = 5;
        break;
    case 14:
        header(im, 2, 0x40, 0x200, 0, 0, 37, 2000000, 20000000);
        im->llio.pins_per_connector = 37;
        break;
    default: return -EINVAL;
    }
    return 0;
}
