/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_module.h - load-time steps shared by the two Pluto-P HAL modules:
 * open the port named by the modparams, upload the firmware, probe.
 */
#ifndef PLUTO_MODULE_H
#define PLUTO_MODULE_H

#include "pluto_common.h"

/* rtapi_print_msg behind a pluto_log. */
void pluto_rtapi_log(void *ctx, int level, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Open `port` (port= spec, or ioaddr/ioaddr_hi/epp_wide), upload firmware
 * file `firmware`, probe the board.  modname ("pluto_servo") prefixes the
 * messages, board ("pluto-servo") goes into LinuxCNC's probe message.
 * 0, or -errno after printing why (the port is closed again). */
int pluto_module_setup(epp_port_t *port, const char *modname, const char *board,
                       const char *portspec, long ioaddr, long ioaddr_hi, int epp_wide,
                       const char *firmware);

#endif /* PLUTO_MODULE_H */
