/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The HAL layer's core (hostmot2.c, tram.c) as the module (module.c) and
 * the unit tests see it: registration with explicit options, the exported
 * HAL function bodies, the TRAM transfers.  Module drivers use
 * module_api.h instead. */
#ifndef HM2_HAL_PRIV_H
#define HM2_HAL_PRIV_H

#include "hm2/hm2.h"
#include "module_api.h"

/* Options hostmot2.c gets from the module (its modparams). */
struct hm2_hal_options {
    struct hm2_options opts;
    hm2_log_fn log;
    void *log_ctx;
};
/* register with explicit options (the module's hm2_register uses its
 * modparams; tests call this directly) */
int hm2_register_opts(hm2_llio_t *llio, const char *config, const struct hm2_hal_options *o);
void hm2_unregister_board(hm2_llio_t *llio);

/* HAL function bodies (exported as <pfx>.read etc.) */
void hm2_read(void *arg, long period);
void hm2_read_request(void *arg, long period);
void hm2_write(void *arg, long period);
void hm2_read_gpio(void *arg, long period);
void hm2_write_gpio(void *arg, long period);
void hm2_pet_watchdog(void *arg, long period);

/* ---- TRAM transfers (tram.c; modules register blocks via module_api.h) ---- */
int hm2_tram_allocate(hostmot2_t *hm2);
int hm2_tram_read(hostmot2_t *hm2);
/* The read in two halves (llio request/receive_queued_reads): queue and
 * send every read; later wait for the reply and fill the buffers. */
int hm2_tram_read_request(hostmot2_t *hm2);
int hm2_tram_read_receive(hostmot2_t *hm2);
int hm2_tram_write(hostmot2_t *hm2);
void hm2_tram_free(hostmot2_t *hm2);

#endif
