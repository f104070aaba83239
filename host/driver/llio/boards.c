/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _POSIX_C_SOURCE 200809L
/* Board facts from spec §16 (connector order = IOPort instance order). */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "hm2/boards.h"

/* 7i96 and 7i96S: terminal blocks, two internal pins and the P1 header
 * (spec §16; the names LinuxCNC's hm2_eth prints). */
static const char *const pins_7i96[] = {
    "TB3-01",        "TB3-02",        "TB3-03",        "TB3-04",        "TB3-05",
    "TB3-06",        "TB3-07",        "TB3-08",        "TB3-09",        "TB3-10",
    "TB3-11",        "TB3-13/TB3-14", "TB3-15/TB3-16", "TB3-17/TB3-18", "TB3-19/TB3-20",
    "TB3-21/TB3-22", "TB3-23/TB3-24", "TB1-02/TB1-03", "TB1-04/TB1-05", "TB1-08/TB1-09",
    "TB1-10/TB1-11", "TB1-14/TB1-15", "TB1-16/TB1-17", "TB1-20/TB1-21", "TB1-22-TB1-23",
    "TB2-02/TB2-03", "TB2-04/TB2-05", "TB2-07/TB2-08", "TB2-10/TB2-11", "TB2-13/TB2-14",
    "TB2-16/TB2-17", "TB2-18/TB2-19", "internal",      "internal",      "P1-01/DB25-01",
    "P1-02/DB25-14", "P1-03/DB25-02", "P1-04/DB25-15", "P1-05/DB25-03", "P1-06/DB25-16",
    "P1-07/DB25-04", "P1-08/DB25-17", "P1-09/DB25-05", "P1-11/DB25-06", "P1-13/DB25-07",
    "P1-15/DB25-08", "P1-17/DB25-09", "P1-19/DB25-10", "P1-21/DB25-11", "P1-23/DB25-12",
    "P1-25/DB25-13",
};
#define NPINS_7I96 ((int)(sizeof(pins_7i96) / sizeof(pins_7i96[0])))

static const struct hm2_board_info boards[] = {
    {"5i20", {"P2", "P3", "P4"}, 3, 24, "2s200pq208", 8, 1, 1, 33333333, 100000000, 0, NULL, 0},
    {"4i65", {"P1", "P3", "P4"}, 3, 24, "2s200pq208", 8, 1, 1, 33333333, 100000000, 0, NULL, 0},
    {"5i22-1.0M", {"P2", "P3", "P4", "P5"}, 4, 24, "3s1000fg320", 8, 1, 1,
     48000000, 96000000, 0, NULL, 0},
    {"5i22-1.5M", {"P2", "P3", "P4", "P5"}, 4, 24, "3s1500fg320", 8, 1, 1,
     48000000, 96000000, 0, NULL, 0},
    {"5i23", {"P2", "P3", "P4"}, 3, 24, "3s400pq208", 2, 1, 1, 48000000, 96000000, 0, NULL, 0},
    {"4i68", {"P1", "P2", "P4"}, 3, 24, "3s400pq208", 4, 1, 1, 48000000, 96000000, 0, NULL, 0},
    {"5i25", {"P3", "P2"}, 2, 17, "6slx9tqg144", 2, 1, 0, 33333333, 200000000, 0, NULL, 0},
    {"6i25", {"P3", "P2"}, 2, 17, "6slx9tqg144", 2, 1, 0, 66666666, 200000000, 0, NULL, 0},
    {"3x20-1.0M", {"P4", "P5", "P6", "P9", "P8", "P7"}, 6, 24, "3s1000fg456", 0, 1, 1, 50000000,
     100000000, 0, NULL, 0},
    {"3x20-1.5M", {"P4", "P5", "P6", "P9", "P8", "P7"}, 6, 24, "3s1500fg456", 0, 1, 1, 50000000,
     100000000, 0, NULL, 0},
    {"3x20-2.0M", {"P4", "P5", "P6", "P9", "P8", "P7"}, 6, 24, "3s2000fg456", 0, 1, 1, 50000000,
     100000000, 0, NULL, 0},
    {"7i43", {"P4", "P3"}, 2, 24, "3s400tq144", 8, 0, 1, 50000000, 100000000, 0, NULL, 0},
    {"7i43-200", {"P4", "P3"}, 2, 24, "3s200tq144", 8, 0, 1, 50000000, 100000000, 0, NULL, 0},
    /* 7i90: EPP, firmware in its own flash; not in spec §16, clocks as the
     * Spartan-6 7i92's (unconfirmed) */
    {"7i90", {"P1", "P2", "P3"}, 3, 24, "6slx9tqg144", 2, 0, 0, 100000000, 200000000, 0, NULL, 0},
    {"7i92", {"P2", "P1"}, 2, 17, "6slx9tqg144", 4, 0, 0, 100000000, 200000000, 1, NULL, 0},
    /* 7I76E: the built-in 7I76 on the on-card port, P1 and P2 headers */
    {"7i76e", {"on-card", "P1", "P2"}, 3, 17, "6slx16ftg256", 4, 0, 0, 100000000, 200000000, 1,
     NULL, 0},
    {"7i96", {"TB3", "TB1", "P1"}, 3, 17, "6slx9tqg144", 4, 0, 0, 100000000, 200000000, 1,
     pins_7i96, NPINS_7I96},
    {"7i96s", {"TB3", "TB1", "P1"}, 3, 17, "T20F256", 4, 0, 0, 100000000, 200000000, 1,
     pins_7i96, NPINS_7I96},
};

static const struct hm2_board_info *lookup_exact(const char *name)
{
    for (size_t i = 0; i < sizeof(boards) / sizeof(boards[0]); i++)
        if (strcasecmp(boards[i].name, name) == 0)
            return &boards[i];
    return NULL;
}

/* Also Mesa's firmware-directory names of the gate-size variants:
 * "5i22-1" is the 5i22-1.0M, "5i22-1.5" the 5i22-1.5M, "3x20-2" the
 * 3x20-2.0M (a virtual board calls itself by the directory its firmware
 * comes from). */
const struct hm2_board_info *hm2_board_lookup(const char *name)
{
    const struct hm2_board_info *b = lookup_exact(name);
    char alt[32];
    if (b || !strchr(name, '-') || strlen(name) + 3 >= sizeof(alt))
        return b;
    snprintf(alt, sizeof(alt), "%sM", name);
    if ((b = lookup_exact(alt)))
        return b;
    snprintf(alt, sizeof(alt), "%s.0M", name);
    return lookup_exact(alt);
}

const struct hm2_board_info *hm2_board_at(int i)
{
    if (i < 0 || (size_t)i >= sizeof(boards) / sizeof(boards[0]))
        return NULL;
    return &boards[i];
}

void hm2_board_fill_llio(const struct hm2_board_info *b, int index, hm2_llio_t *llio)
{
    /* llio names use the model part only: "hm2_5i22.0", "hm2_3x20.0" */
    char model[16];
    snprintf(model, sizeof(model), "%s", b->name);
    char *dash = strchr(model, '-');
    if (dash)
        *dash = '\0';
    snprintf(llio->name, sizeof(llio->name), "hm2_%s.%d", model, index);
    llio->num_ioport_connectors = b->num_connectors;
    llio->pins_per_connector = b->pins_per_connector;
    for (int i = 0; i < HM2_LLIO_MAX_CONNECTORS; i++)
        llio->ioport_connector_name[i] = i < b->num_connectors ? b->connectors[i] : NULL;
    llio->fpga_part_number = b->fpga_part;
    llio->num_leds = b->num_leds;
    llio->threadsafe = b->threadsafe;
    llio->io_pin_names = b->pin_names;
    llio->num_io_pin_names = b->num_pin_names;
}
