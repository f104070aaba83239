/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hmid.h - a probed board's firmware listing in mesaflash's --readhmid
 * layout (IDROM header, modules, pin-out), shared by hm2flash --readhmid
 * and hm2pinout --pin-file.  No HAL calls.
 */
#ifndef HM2_HMID_H
#define HM2_HMID_H

#include <stdio.h>

#include "hm2/hm2.h"

void hm2_print_hmid(const hostmot2_t *hm2, FILE *f);

#endif /* HM2_HMID_H */
