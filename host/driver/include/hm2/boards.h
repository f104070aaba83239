/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * boards.h - the Anything-I/O board table (spec §16): what each board's
 * llio reports (connector names, pins per connector, FPGA part, LEDs).
 * Backends and the pinout tool look boards up here instead of repeating it.
 */
#ifndef HM2_BOARDS_H
#define HM2_BOARDS_H

#include "hm2/llio.h"

#ifdef __cplusplus
extern "C" {
#endif

struct hm2_board_info {
    const char *name;      /* llio base name without "hm2_": "5i20" */
    const char *connectors[HM2_LLIO_MAX_CONNECTORS];
    int num_connectors;
    int pins_per_connector;
    const char *fpga_part; /* as in .BIT 'b' chunks */
    int num_leds;
    int threadsafe;        /* PCI: 1, EPP: 0 */
    int programmable;      /* FPGA loaded by the host (not flash-configured) */
    unsigned clock_low, clock_high; /* stock IDROM clocks, informational */
    int ethernet;          /* LBP16 over UDP (hm2_eth) */
    /* Per-pin connector names (boards whose connectors are not one header
     * per port, like the 7i96): num_pin_names entries; NULL = none. */
    const char *const *pin_names;
    int num_pin_names;
};

/* Case-insensitive lookup ("5i20", "7I43"; a gate-size variant also by
 * its firmware directory, "5i22-1.5" = "5i22-1.5M"); NULL if unknown. */
const struct hm2_board_info *hm2_board_lookup(const char *name);
/* NULL-terminated iteration. */
const struct hm2_board_info *hm2_board_at(int i);
/* Fill the geometry/identity part of an llio from a board entry; name
 * becomes "hm2_<board>.<index>". */
void hm2_board_fill_llio(const struct hm2_board_info *b, int index, hm2_llio_t *llio);

#ifdef __cplusplus
}
#endif

#endif /* HM2_BOARDS_H */
