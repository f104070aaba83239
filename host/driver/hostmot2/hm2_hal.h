/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Internal interface of the HAL layer: TRAM and the module drivers. */
#ifndef HM2_HAL_PRIV_H
#define HM2_HAL_PRIV_H

#include "hm2/hm2.h"

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
void hm2_write(void *arg, long period);
void hm2_read_gpio(void *arg, long period);
void hm2_write_gpio(void *arg, long period);
void hm2_pet_watchdog(void *arg, long period);

/* ---- TRAM: the register blocks transferred every period ---- */
int hm2_tram_add_read(hostmot2_t *hm2, uint32_t addr, uint32_t **buf, int words);
int hm2_tram_add_write(hostmot2_t *hm2, uint32_t addr, uint32_t **buf, int words);
int hm2_tram_allocate(hostmot2_t *hm2);
int hm2_tram_read(hostmot2_t *hm2);
int hm2_tram_write(hostmot2_t *hm2);
void hm2_tram_free(hostmot2_t *hm2);

/* ---- module drivers ----
 * setup: allocate state, export HAL objects, register TRAM blocks
 * process_read: after the TRAM read    prepare_write: before the TRAM write
 * write_changed: immediate writes of configuration that changed
 * force_write: write all configuration (load, recovery)
 * cleanup: free state */
int hm2_ioport_setup(hostmot2_t *hm2);
void hm2_ioport_process_read(hostmot2_t *hm2);
void hm2_ioport_prepare_write(hostmot2_t *hm2);
void hm2_ioport_write_changed(hostmot2_t *hm2);
void hm2_ioport_force_write(hostmot2_t *hm2);
int hm2_ioport_read_gpio(hostmot2_t *hm2);
int hm2_ioport_write_gpio(hostmot2_t *hm2);
void hm2_ioport_enable_module_outputs(hostmot2_t *hm2);
void hm2_ioport_cleanup(hostmot2_t *hm2);

int hm2_watchdog_setup(hostmot2_t *hm2);
void hm2_watchdog_process_read(hostmot2_t *hm2);
void hm2_watchdog_prepare_write(hostmot2_t *hm2, long period);
void hm2_watchdog_write_changed(hostmot2_t *hm2);
void hm2_watchdog_force_write(hostmot2_t *hm2);
int hm2_watchdog_pet(hostmot2_t *hm2);
bool hm2_watchdog_has_bit(const hostmot2_t *hm2);
void hm2_watchdog_clear_bite(hostmot2_t *hm2);
void hm2_watchdog_force_bite(hostmot2_t *hm2);
void hm2_watchdog_cleanup(hostmot2_t *hm2);

int hm2_encoder_setup(hostmot2_t *hm2);
void hm2_encoder_process_read(hostmot2_t *hm2, long period);
void hm2_encoder_write_changed(hostmot2_t *hm2);
void hm2_encoder_force_write(hostmot2_t *hm2);
void hm2_encoder_cleanup(hostmot2_t *hm2);

int hm2_stepgen_setup(hostmot2_t *hm2);
void hm2_stepgen_process_read(hostmot2_t *hm2, long period);
void hm2_stepgen_prepare_write(hostmot2_t *hm2, long period);
void hm2_stepgen_write_changed(hostmot2_t *hm2);
void hm2_stepgen_force_write(hostmot2_t *hm2);
void hm2_stepgen_cleanup(hostmot2_t *hm2);

int hm2_pwmgen_setup(hostmot2_t *hm2);
void hm2_pwmgen_prepare_write(hostmot2_t *hm2);
void hm2_pwmgen_write_changed(hostmot2_t *hm2);
void hm2_pwmgen_force_write(hostmot2_t *hm2);
void hm2_pwmgen_cleanup(hostmot2_t *hm2);

int hm2_led_setup(hostmot2_t *hm2);
void hm2_led_write_changed(hostmot2_t *hm2);
void hm2_led_force_write(hostmot2_t *hm2);
void hm2_led_cleanup(hostmot2_t *hm2);

int hm2_raw_setup(hostmot2_t *hm2);
void hm2_raw_process_read(hostmot2_t *hm2);
void hm2_raw_write(hostmot2_t *hm2);
void hm2_raw_cleanup(hostmot2_t *hm2);

/* Immediate configuration write: on failure the board needs a reset (the
 * next write() tries to recover).  Returns 0 or the llio's error. */
int hm2_write_cfg(hostmot2_t *hm2, uint32_t addr, uint32_t val);

/* hal_malloc that zeroes and reports failure */
void *hm2_hal_zalloc(hostmot2_t *hm2, size_t size, const char *what);

/* Report a HAL export failure (r < 0) naming the object; returns r. */
int hm2_hal_fail(hostmot2_t *hm2, int r, const char *what);

#endif
