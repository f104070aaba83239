/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_module.h - load-time steps shared by the two Pluto-P HAL modules:
 * open the port named by the modparams, upload the firmware, probe.
 */
#ifndef PLUTO_MODULE_H
#define PLUTO_MODULE_H

#include "hal.h"
#include "pluto_common.h"
#include "rtapi.h"

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

/* The modparams every Pluto-P module has, with LinuxCNC's names and
 * texts, plus port= and firmware=.  FW ("pluto_servo.rbf") is the default
 * firmware named in firmware='s text.  Expands to static definitions in
 * the module's own file (rtapi_app finds them there). */
#define PLUTO_MODULE_PARAMS(FW)                                                             \
    static int ioaddr = 0x378;                                                              \
    RTAPI_MP_INT(ioaddr, "Address of parallel port where pluto-p is attached");             \
    static int ioaddr_hi = 0;                                                               \
    RTAPI_MP_INT(ioaddr_hi,                                                                 \
                 "Secondary address of parallel port (0 = ioaddr+0x400, -1 = none)");       \
    static int epp_wide = 1;                                                                \
    RTAPI_MP_INT(epp_wide, "Use 16- and 32-bit EPP transfers with hardware EPP");           \
    static int watchdog = 1;                                                                \
    RTAPI_MP_INT(watchdog, "Enable hardware watchdog to tristate outputs if EMC crashes");  \
    static char *port = NULL;                                                               \
    RTAPI_MP_STRING(port, "Port: raw:ADDR, ppdev:/dev/parportN, gpiod:CHIP:LINES or "       \
                          "sim:SOCKET (overrides ioaddr)");                                 \
    static char *firmware = NULL;                                                           \
    RTAPI_MP_STRING(firmware,                                                               \
                    "Firmware file uploaded at load (default " FW " on the firmware path)")

/* The skeleton of both realtime modules: what differs is described here,
 * the load and unload sequence is pluto_module_load/unload. */
struct pluto_module_desc {
    const char *modname;          /* "pluto_servo": HAL component, messages */
    const char *board;            /* "pluto-servo": HAL names, probe message */
    const char *default_firmware; /* "pluto_servo.rbf" */
    size_t block_size;            /* the driver's HAL-memory block */
    size_t port_offset;           /* offsetof(block, its epp_port_t) */
    /* after the upload: fill the block (port, modparams), export the HAL
     * pins and parameters, set the defaults.  0 or a HAL error. */
    int (*init)(void *block, int comp_id);
    /* exported as BOARD.read and BOARD.write, with the block as argument */
    void (*read)(void *block, long period);
    void (*write)(void *block, long period);
};
/* The modparams every Pluto-P module has. */
struct pluto_module_args {
    const char *port;
    long ioaddr, ioaddr_hi;
    int epp_wide;
    const char *firmware; /* NULL or "": desc->default_firmware */
};
/* hal_init, the block in HAL memory, port + upload + probe, init, the two
 * functions, hal_ready.  0 with *block and *comp_id set, or -errno with
 * everything undone (*block NULL, *comp_id -1) after printing why. */
int pluto_module_load(const struct pluto_module_desc *d, const struct pluto_module_args *a,
                      void **block, int *comp_id);
/* rtapi_app_exit: close the port, hal_exit. */
void pluto_module_unload(const struct pluto_module_desc *d, void **block, int *comp_id);

/* The HAL objects both boards have, named PFX.dout.NN (+ PFX.dout.NN-invert)
 * for ndout outputs and PFX.din.NN (+ PFX.din.NN-not) for ndin inputs.
 * 0 or the first HAL error. */
int pluto_export_dio(int comp_id, const char *pfx, hal_bit_t **dout, hal_bit_t *dout_invert,
                     int ndout, hal_bit_t **din, hal_bit_t **din_not, int ndin);
/* PFX.communication-error, PFX.debug-0, PFX.debug-1. */
int pluto_export_diag(int comp_id, const char *pfx, hal_u32_t *communication_error,
                      hal_s32_t *debug_0, hal_s32_t *debug_1);

#endif /* PLUTO_MODULE_H */
