/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2pinout's sim: source (source_sim.c; built with the hm2_sim backend). */
#ifndef HM2PINOUT_SOURCE_SIM_H
#define HM2PINOUT_SOURCE_SIM_H

#include "hm2/llio.h"

/* Connect to the virtual board at socket path, naming it
 * hm2_<board>.<index>.  0, or -errno after printing why. */
int hm2pinout_open_sim(const char *path, int index, hm2_llio_t **llio, void **handle);
void hm2pinout_close_sim(void *handle);

#endif
