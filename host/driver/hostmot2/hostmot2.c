/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2_register/hm2_unregister and the per-period HAL functions (spec §11). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2_hal.h"
#include "modules.h"

/* What the exported functions get as their argument: a small block in HAL
 * memory that outlives the board, so a function that runs once more after
 * unregister finds board == NULL instead of freed memory. */
struct hm2_funct_handle {
    hostmot2_t *volatile board;
};

/* The module phases, walked over the module table (modules.c) in its
 * order; cleanup in reverse. */
static void cleanup_modules(hostmot2_t *hm2)
{
    for (int i = hm2_num_modules - 1; i >= 0; i--)
        if (hm2_modules[i]->cleanup)
            hm2_modules[i]->cleanup(hm2);
    hm2_tram_free(hm2);
}

static int setup_modules(hostmot2_t *hm2)
{
    for (int i = 0; i < hm2_num_modules; i++) {
        int r = hm2_modules[i]->setup ? hm2_modules[i]->setup(hm2) : 0;
        if (r)
            return r;
    }
    return 0;
}

static void force_write_all(hostmot2_t *hm2)
{
    for (int i = 0; i < hm2_num_modules; i++)
        if (hm2_modules[i]->force_write)
            hm2_modules[i]->force_write(hm2);
}

static void process_read(hostmot2_t *hm2, long period)
{
    for (int i = 0; i < hm2_num_modules; i++)
        if (hm2_modules[i]->process_read)
            hm2_modules[i]->process_read(hm2, period);
}

static void prepare_write(hostmot2_t *hm2, long period)
{
    for (int i = 0; i < hm2_num_modules; i++)
        if (hm2_modules[i]->prepare_write)
            hm2_modules[i]->prepare_write(hm2, period);
}

static void write_changed(hostmot2_t *hm2)
{
    for (int i = 0; i < hm2_num_modules; i++)
        if (hm2_modules[i]->write_changed)
            hm2_modules[i]->write_changed(hm2);
}

static void io_failed(hostmot2_t *hm2)
{
    *hm2->io_error = 1;
    hm2->needs_reset = true;
}

/* <pfx>.read-request (boards with request/receive_queued_reads): send this
 * period's reads now; <pfx>.read then only waits for the reply.  A second
 * request before the read replaces the first. */
void hm2_read_request(void *arg, long period)
{
    hostmot2_t *hm2 = ((struct hm2_funct_handle *)arg)->board;
    if (!hm2 || *hm2->io_error)
        return;
    hm2->llio->period_ns = period;
    hm2->read_requested = false;
    if (hm2_tram_read_request(hm2)) {
        hm2_msg(hm2, HM2_ERR, "read request failed, setting io_error (clear it to retry)");
        io_failed(hm2);
        return;
    }
    hm2->read_requested = true;
}

void hm2_read(void *arg, long period)
{
    hostmot2_t *hm2 = ((struct hm2_funct_handle *)arg)->board;
    if (!hm2 || *hm2->io_error) {
        if (hm2)
            hm2->read_requested = false;
        return;
    }
    hm2->llio->period_ns = period;
    bool requested = hm2->read_requested;
    hm2->read_requested = false;
    if (requested ? hm2_tram_read_receive(hm2) : hm2_tram_read(hm2)) {
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
    hm2->llio->period_ns = period;
    if (hm2->needs_reset && !bitten && !recover(hm2))
        return;
    prepare_write(hm2, period);
    if (hm2_tram_write(hm2)) {
        hm2_msg(hm2, HM2_ERR, "write failed, setting io_error (clear it to retry)");
        io_failed(hm2);
        return;
    }
    write_changed(hm2);
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
    if (hm2->llio->request_queued_reads &&
        (r = hal_export_functf(hm2_read_request, h, 1, 0, id, "%s.read-request", pfx)))
        return hm2_hal_fail(hm2, r, "read-request");
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
    if ((r = setup_modules(hm2)))
        return r;
    return hm2_tram_allocate(hm2);
}

/* Load steps 8: configuration out, one read to zero the counters, one write. */
static int first_transfer(hostmot2_t *hm2)
{
    force_write_all(hm2);
    if (hm2_tram_read(hm2))
        goto comm;
    process_read(hm2, HM2_LOAD_PERIOD);
    prepare_write(hm2, HM2_LOAD_PERIOD);
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
