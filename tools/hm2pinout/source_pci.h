/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2pinout's pci: source (source_pci.c; built when the hm2_pci backend is). */
#ifndef HM2PINOUT_SOURCE_PCI_H
#define HM2PINOUT_SOURCE_PCI_H

#include "hm2/llio.h"

/* Open the board at PCI address addr ("" = the first Mesa board found),
 * naming it hm2_<board>.<index>.  0, or -errno after printing why. */
int hm2pinout_open_pci(const char *addr, int index, hm2_llio_t **llio, void **handle);
void hm2pinout_close_pci(void *handle);

#endif
