/* SPDX-License-Identifier: GPL-2.0-or-later */
/* source_pci.h - hm2flash's pci: source (source_pci.c). */
#ifndef HM2FLASH_SOURCE_PCI_H
#define HM2FLASH_SOURCE_PCI_H

#include <stddef.h>

#include "hm2/llio.h"

/* addr: "" (first board of that type) or "0000:01:00.0"; board: llio model
 * ("5i25").  0, or -errno with the reason in why. */
int hm2flash_open_pci(const char *addr, const char *board, hm2_llio_t **llio, void **handle,
                      char *why, size_t whylen);
void hm2flash_close_pci(void *handle);

#endif /* HM2FLASH_SOURCE_PCI_H */
