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

/* The skeleton of both realtime modules: what differs is described here,
 * the load and unload sequence is pluto_module_load/unload. */
struct pluto_module_desc {
    const char *modname;          /* "pluto_servo": HAL component, messages */
    const char *board;            /* "pluto-servo": probe message */
    const char *default_firmware; /* "pluto_servo.rbf" */
    size_t block_size;            /* the driver's HAL-memory block */
    epp_port_t *(*port_of)(void *block);
    /* after the upload: fill the block (port, modparams), export the HAL
     * objects and functions, set the defaults.  0 or a HAL error. */
    int (*init)(void *block, int comp_id);
};
/* The modparams every Pluto-P module has. */
struct pluto_module_args {
    const char *port;
    long ioaddr, ioaddr_hi;
    int epp_wide;
    const char *firmware; /* NULL or "": desc->default_firmware */
};
/* hal_init, the block in HAL memory, port + upload + probe, init,
 * hal_ready.  0 with *block and *comp_id set, or -errno with everything
 * undone (*block NULL, *comp_id -1) after printing why. */
int pluto_module_load(const struct pluto_module_desc *d, const struct pluto_module_args *a,
                      void **block, int *comp_id);
/* rtapi_app_exit: close the port, hal_exit. */
void pluto_module_unload(const struct pluto_module_desc *d, void **block, int *comp_id);

#endif /* PLUTO_MODULE_H */
