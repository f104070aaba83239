/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _POSIX_C_SOURCE 200809L
/* Board facts from spec §16 (connector order = IOPort instance order). */
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "hm2/boards.h"

static const struct hm2_board_info boards[] = {
    {"5i20", {"P2", "P3", "P4"}, 3, 24, "2s200pq208", 8, 1, 1, 33333333, 100000000},
    {"4i65", {"P1", "P3", "P4"}, 3, 24, "2s200pq208", 8, 1, 1, 33333333, 100000000},
    {"5i22-1.0M", {"P2", "P3", "P4", "P5"}, 4, 24, "3s1000fg320", 8, 1, 1, 48000000, 96000000},
    {"5i22-1.5M", {"P2", "P3", "P4", "P5"}, 4, 24, "3s1500fg320", 8, 1, 1, 48000000, 96000000},
    {"5i23", {"P2", "P3", "P4"}, 3, 24, "3s400pq208", 2, 1, 1, 48000000, 96000000},
    {"4i68", {"P1", "P2", "P4"}, 3, 24, "3s400pq208", 4, 1, 1, 48000000, 96000000},
    {"5i25", {"P3", "P2"}, 2, 17, "6slx9tqg144", 2, 1, 0, 33333333, 200000000},
    {"6i25", {"P3", "P2"}, 2, 17, "6slx9tqg144", 2, 1, 0, 66666666, 200000000},
    {"3x20-1.0M", {"P4", "P5", "P6", "P9", "P8", "P7"}, 6, 24, "3s1000fg456", 0, 1, 1, 50000000,
     100000000},
    {"3x20-1.5M", {"P4", "P5", "P6", "P9", "P8", "P7"}, 6, 24, "3s1500fg456", 0, 1, 1, 50000000,
     100000000},
    {"3x20-2.0M", {"P4", "P5", "P6", "P9", "P8", "P7"}, 6, 24, "3s2000fg456", 0, 1, 1, 50000000,
     100000000},
    {"7i43", {"P4", "P3"}, 2, 24, "3s400tq144", 8, 0, 1, 50000000, 100000000},
    {"7i43-200", {"P4", "P3"}, 2, 24, "3s200tq144", 8, 0, 1, 50000000, 100000000},
    {"7i92", {"P2", "P1"}, 2, 17, "", 4, 0, 0, 100000000, 200000000},
};

const struct hm2_board_info *hm2_board_lookup(const char *name)
{
    for (size_t i = 0; i < sizeof(boards) / sizeof(boards[0]); i++)
        if (strcasecmp(boards[i].name, name) == 0)
            return &boards[i];
    return NULL;
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
}
