/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The JTAG lines of a virtual board for the GPIO cable engine (jtag_sim.c). */
#ifndef HM2FLASH_JTAG_SIM_H
#define HM2FLASH_JTAG_SIM_H

#include <stddef.h>

#include "hm2/jtag_gpio.h"

/* Connect to the vboard at socket `path`.  0, or -errno with the reason in
 * err. */
int jtag_sim_lines_open(struct jtag_gpio_lines *lines, const char *path, char *err,
                        size_t errlen);

#endif
