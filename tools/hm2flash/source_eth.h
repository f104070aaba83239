/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2flash's Ethernet boards: hm2 over LBP16, the flash through LBP16
 * memory space 3 (source_eth.c). */
#ifndef HM2FLASH_SOURCE_ETH_H
#define HM2FLASH_SOURCE_ETH_H

#include <stddef.h>

#include "hm2/cfgflash.h"

/* Connect to the board at IPv4 address ip; fill io (llio and flash ops).
 * 0, or -errno with the reason in why (at least 300 bytes). */
int hm2flash_open_eth(const char *ip, struct hm2_flash_io *io, void **handle, char *why,
                      size_t whylen);
/* The board-table name of the board that answered ("7i92"). */
const char *hm2flash_eth_board(void *handle);
void hm2flash_close_eth(void *handle);

#endif
