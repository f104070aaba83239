/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2_register/hm2_unregister and the per-period HAL functions (spec §11). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2_hal.h"

/* What the exported functions get as their argument: a small block in HAL
 * memory that outlives the board, so a function that runs once more after
 * unregister finds board == NULL instead of freed memory. */
struct hm2_funct_handle {
    hostmot2_t *volatile board;
};

void *hm2_hal_zalloc(hostmot2_t *hm2, size_t size, const char *what)
{
    void *p = hal_malloc((long)size);
    if (!p) {
        hm2_msg(hm2, HM2_ERR, "out of HAL memory allocating %s (%zu bytes)", what, size);
        return NULL;
    }
    memset(p, 0, size);
    return p;
}

int hm2_write_cfg(hostmot2_t *hm2, uint32_t addr, uint32_t val)
{
    int r = hm2_write_reg(hm2, addr, val);
    if (r) {
        hm2_msg(hm2, HM2_ERR, "error writing 0x%08X to register 0x%04X: %s", val, addr,
                strerror(-r));
        hm2->needs_reset = true;
    }
    return r;
}

int hm2_hal_fail(hostmot2_t *hm2, int r, const char *what)
{
    hm2_msg(hm2, HM2_ERR, "error %d (%s) exporting %s.%s to HAL", r, strerror(-r),
            hm2->llio->name, what);
    return r;
}

static void cleanup_modules(hostmot2_t *hm2)
{
    hm2_raw_cleanup(hm2);
    hm2_led_cleanup(hm2);
    hm2_pwmgen_cleanup(hm2);
    hm2_stepgen_cleanup(hm2);
    hm2_encoder_cleanup(hm2);
    hm2_watchdog_cleanup(hm2);
    hm2_ioport_cleanup(hm2);
    hm2_tram_free(hm2);
}

static void force_write_all(hostmot2_t *hm2)
{
    hm2_ioport_force_write(hm2);
    hm2_watchdog_force_write(hm2);
    hm2_encoder_force_write(hm2);
    hm2_stepgen_force_write(hm2);
    hm2_pwmgen_force_write(hm2);
    hm2_led_force_write(hm2);
}

static void process_read(hostmot2_t *hm2, long period)
{
    hm2_watchdog_process_read(hm2);
    hm2_ioport_process_read(hm2);
    hm2_encoder_process_read(hm2, period);
    hm2_stepgen_process_read(hm2, period);
    hm2_raw_process_read(hm2);
}

static void io_failed(hostmot2_t *hm2)
{
    *hm2->io_error = 1;
    hm2->needs_reset = true;
}

void hm2_read(void *arg, long period)
{
    hostmot2_t *hm2 = ((struct hm2_funct_handle *)arg)->board;
    if (!hm2 || *hm2->io_error)
        return;
    if (hm2_tram_read(hm2)) {
        hm2_msg(hm2, HM2_ERR, "read failed, setting io_error (clear it to retry)");
        io_failed(hm2);
        return;
    }
    process_read(hm2, period);
}

/* After a watchdog bite or an I/O error: once the user has cleared
 * has_bit / io_error, rewrite every module's configuration. */
static bool recover(hostmot2_t *hm2)
{
    if (hm2_watchdog_has_bit(hm2))
        return false;
    hm2_msg(hm2, HM2_PRINT, "trying to recover from IO error or Watchdog bite");
    hm2->needs_reset = false;
    hm2_watchdog_clear_bite(hm2);
    force_write_all(hm2);
    if (hm2->needs_reset) {
        hm2_msg(hm2, HM2_ERR, "error recovery failed");
        *hm2->io_error = 1;
        return false;
    }
    hm2_msg(hm2, HM2_PRINT, "error recover successful!");
    return true;
}

void hm2_write(void *arg, long period)
{
    hostmot2_t *hm2 = ((struct hm2_funct_handle *)arg)->board;
    if (!hm2 || *hm2->io_error)
        return;
    /* After a bite the transfers go on as in LinuxCNC 2.9 (the pet, the
     * rates, the GPIO outputs: the board keeps its outputs safe until the
     * bite is cleared); only the full configuration rewrite waits until the
     * user clears has_bit. */
    bool bitten = hm2_watchdog_has_bit(hm2);
    if (hm2->needs_reset && !bitten && !recover(hm2))
        return;
    hm2_ioport_enable_module_outputs(hm2);
    hm2_watchdog_prepare_write(hm2, period);
    hm2_ioport_prepare_write(hm2);
    hm2_pwmgen_prepare_write(hm2);
    hm2_stepgen_prepare_write(hm2, period);
    if (hm2_tram_write(hm2)) {
        hm2_msg(hm2, HM2_ERR, "write failed, setting io_error (clear it to retry)");
        io_failed(hm2);
        return;
    }
    hm2_ioport_write_changed(hm2);
    hm2_watchdog_write_changed(hm2);
    hm2_pwmgen_write_changed(hm2);
    hm2_stepgen_write_changed(hm2);
    hm2_encoder_write_changed(hm2);
    hm2_led_write_changed(hm2);
    hm2_raw_write(hm2);
    if (hm2->needs_reset && !hm2_watchdog_has_bit(hm2)) {
        hm2_msg(hm2, HM2_ERR, "configuration write failed, setting io_error (clear it to retry)");
        *hm2->io_error = 1;
    }
}

void hm2_read_gpio(void *arg, long period)
{
    hostmot2_t *hm2 = ((struct hm2_funct_handle *)arg)->board;
    (void)period;
    if (!hm2 || *hm2->io_error)
        return;
    if (hm2_ioport_read_gpio(hm2)) {
        hm2_msg(hm2, HM2_ERR, "read_gpio failed, setting io_error (clear it to retry)");
        io_failed(hm2);
    }
}

void hm2_write_gpio(void *arg, long period)
{
    hostmot2_t *hm2 = ((struct hm2_funct_handle *)arg)->board;
    (void)period;
    if (!hm2 || *hm2->io_error || hm2->needs_reset)
        return;
    if (hm2_ioport_write_gpio(hm2)) {
        hm2_msg(hm2, HM2_ERR, "write_gpio failed, setting io_error (clear it to retry)");
        io_failed(hm2);
    }
}

void hm2_pet_watchdog(void *arg, long period)
{
    hostmot2_t *hm2 = ((struct hm2_funct_handle *)arg)->board;
    (void)period;
    if (!hm2 || *hm2->io_error || (hm2->needs_reset && !hm2_watchdog_has_bit(hm2)))
        return;
    if (hm2_watchdog_pet(hm2)) {
        hm2_msg(hm2, HM2_ERR, "pet_watchdog failed, setting io_error (clear it to retry)");
        io_failed(hm2);
    }
}

static int export_functions(hostmot2_t *hm2, struct hm2_funct_handle *h)
{
    const char *pfx = hm2->llio->name;
    int id = hm2->llio->comp_id, r;
    if ((r = hal_export_functf(hm2_read, h, 1, 0, id, "%s.read", pfx)))
        return hm2_hal_fail(hm2, r, "read");
    if ((r = hal_export_functf(hm2_write, h, 1, 0, id, "%s.write", pfx)))
        return hm2_hal_fail(hm2, r, "write");
    if (hm2->watchdog_s) {
        /* seed name, and the hyphenated spelling its function list uses */
        if ((r = hal_export_functf(hm2_pet_watchdog, h, 1, 0, id, "%s.pet_watchdog", pfx)))
            return hm2_hal_fail(hm2, r, "pet_watchdog");
        if ((r = hal_export_functf(hm2_pet_watchdog, h, 1, 0, id, "%s.pet-watchdog", pfx)))
            return hm2_hal_fail(hm2, r, "pet-watchdog");
    }
    if (hm2->llio->threadsafe) {
        if ((r = hal_export_functf(hm2_read_gpio, h, 1, 0, id, "%s.read_gpio", pfx)))
            return hm2_hal_fail(hm2, r, "read_gpio");
        if ((r = hal_export_functf(hm2_write_gpio, h, 1, 0, id, "%s.write_gpio", pfx)))
            return hm2_hal_fail(hm2, r, "write_gpio");
    }
    return 0;
}

static int setup_hal(hostmot2_t *hm2)
{
    int r;
    hm2->io_error = hm2_hal_zalloc(hm2, sizeof(*hm2->io_error), "io_error");
    if (!hm2->io_error)
        return -ENOMEM;
    if ((r = hal_param_bit_newf(HAL_RW, hm2->io_error, hm2->llio->comp_id, "%s.io_error",
                                hm2->llio->name)))
        return hm2_hal_fail(hm2, r, "io_error");
    if ((r = hm2_ioport_setup(hm2)) || (r = hm2_watchdog_setup(hm2)) ||
        (r = hm2_encoder_setup(hm2)) || (r = hm2_stepgen_setup(hm2)) ||
        (r = hm2_pwmgen_setup(hm2)) || (r = hm2_led_setup(hm2)) || (r = hm2_raw_setup(hm2)))
        return r;
    return hm2_tram_allocate(hm2);
}

/* Load steps 8: configuration out, one read to zero the counters, one write. */
static int first_transfer(hostmot2_t *hm2)
{
    force_write_all(hm2);
    if (hm2_tram_read(hm2))
        goto comm;
    process_read(hm2, 0);
    hm2_ioport_prepare_write(hm2);
    hm2_pwmgen_prepare_write(hm2);
    hm2_stepgen_prepare_write(hm2, 0);
    if (hm2_tram_write(hm2) || hm2->needs_reset)
        goto comm;
    return 0;
comm:
    hm2_msg(hm2, HM2_ERR, "comm errors while initializing firmware!");
    return -EIO;
}

int hm2_register_opts(hm2_llio_t *llio, const char *config, const struct hm2_hal_options *o)
{
    int r;
    if (llio && llio->hm2) {
        hm2_msg_core(o->log, o->log_ctx, HM2_ERR, "board %s is already registered", llio->name);
        return -EEXIST;
    }
    hostmot2_t *hm2 = hm2_probe(llio, config, &o->opts, o->log, o->log_ctx, &r);
    if (!hm2)
        return r;
    struct hm2_funct_handle *h = NULL;
    if ((r = setup_hal(hm2)) || (r = first_transfer(hm2)))
        goto fail;
    h = hm2_hal_zalloc(hm2, sizeof(*h), "function handle");
    if (!h) {
        r = -ENOMEM;
        goto fail;
    }
    h->board = hm2;
    hm2->handle = h;
    if (hm2->debug.modules)
        hm2_print_modules(hm2);
    hm2_print_pin_usage(hm2);
    if ((r = export_functions(hm2, h)))
        goto fail;
    llio->hm2 = hm2;
    hm2->registered = true;
    hm2_msg(hm2, HM2_PRINT, "registered");
    return 0;
fail:
    if (h)
        h->board = NULL;
    cleanup_modules(hm2);
    hm2_free(hm2);
    return r;
}

void hm2_unregister_board(hm2_llio_t *llio)
{
    if (!llio || !llio->hm2)
        return;
    hostmot2_t *hm2 = llio->hm2;
    if (hm2->handle)
        ((struct hm2_funct_handle *)hm2->handle)->board = NULL;
    /* make the watchdog bite so every output goes to a safe input state */
    hm2_watchdog_force_bite(hm2);
    hm2_msg(hm2, HM2_PRINT, "unregistered");
    cleanup_modules(hm2);
    llio->hm2 = NULL;
    hm2_free(hm2);
}
