/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * module_api.h - what a hostmot2 module driver (ioport.c, watchdog.c,
 * encoder.c, stepgen.c, pwmgen.c, led.c, raw.c) sees of the HAL layer, and
 * what it gives the core in return.
 *
 * Layers, each using only the ones below it:
 *   hostmot2.c (register, read/write functions, recovery)
 *     -> modules.c (the ordered table of module operations)
 *       -> the module files (one per module, each exports its ops)
 *         -> this header's helpers (helpers.c, tram.c) and hm2core
 */
#ifndef HM2_MODULE_API_H
#define HM2_MODULE_API_H

#include "hm2/hm2.h"

/* A module's part in the per-board life cycle.  Any entry may be NULL.
 *   setup          allocate state, export HAL objects, register TRAM blocks
 *   process_read   after every TRAM read
 *   prepare_write  before every TRAM write: fill the module's write blocks.
 *                  period is the HAL thread period, or HM2_LOAD_PERIOD for
 *                  the one transfer at load (no HAL write() yet)
 *   write_changed  after the TRAM write: immediate writes of the
 *                  configuration that changed
 *   force_write    write all configuration (load, recovery)
 *   cleanup        free the module's state (HAL memory stays with HAL) */
struct hm2_module_ops {
    const char *name;
    int (*setup)(hostmot2_t *hm2);
    void (*process_read)(hostmot2_t *hm2, long period);
    void (*prepare_write)(hostmot2_t *hm2, long period);
    void (*write_changed)(hostmot2_t *hm2);
    void (*force_write)(hostmot2_t *hm2);
    void (*cleanup)(hostmot2_t *hm2);
};

#define HM2_LOAD_PERIOD 0L

/* ---- helpers for the modules (helpers.c) ---- */

/* Immediate configuration write: on failure the board needs a reset (the
 * next write() tries to recover).  Returns 0 or the llio's error. */
int hm2_write_cfg(hostmot2_t *hm2, uint32_t addr, uint32_t val);
/* hal_malloc that zeroes and reports failure */
void *hm2_hal_zalloc(hostmot2_t *hm2, size_t size, const char *what);
/* Report a HAL export failure (r < 0) naming the object; returns r. */
int hm2_hal_fail(hostmot2_t *hm2, int r, const char *what);

/* Let module `gtag` drive its output pins now, before the first HAL
 * write() turns every module output on (ioport.c): for protocols that run
 * at load, like Smart Serial discovery.  0, or -errno. */
int hm2_ioport_early_outputs(hostmot2_t *hm2, int gtag);

/* ---- TRAM: the register blocks transferred every period (tram.c) ---- */
int hm2_tram_add_read(hostmot2_t *hm2, uint32_t addr, uint32_t **buf, int words);
int hm2_tram_add_write(hostmot2_t *hm2, uint32_t addr, uint32_t **buf, int words);

#endif
