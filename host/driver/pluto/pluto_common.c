/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Shared Pluto-P driver code (see pluto_common.h, docs/pluto_servo.md). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/bitfile.h"
#include "pluto_common.h"

int64_t pluto_extend(int64_t old, uint32_t newlow, int bits)
{
    int64_t mask = ((int64_t)1 << bits) - 1;
    int64_t low = (int64_t)newlow & mask;
    int64_t c1 = (old & ~mask) | low;
    int64_t c2 = (old & mask) < low ? c1 - ((int64_t)1 << bits) : c1 + ((int64_t)1 << bits);
    int64_t d = old - c1;
    if (d < 0)
        d = -d;
    return d > (mask / 2) ? c2 : c1;
}

/* Bytes per flush during the upload: the sim backend sends one request per
 * flush; direct backends execute as they go. */
#define UPLOAD_CHUNK 512u

int pluto_upload(epp_port_t *port, const uint8_t *image, size_t len, const struct pluto_log *log)
{
    int r, i;
    if (!port || !image || len == 0)
        return -EINVAL;
    if (len > PLUTO_UPLOAD_BYTES)
        len = PLUTO_UPLOAD_BYTES;
    if ((r = epp_control_write(port, 0x04)))
        goto out;
    if (port->has_ecr && (r = epp_ecr_write(port, 0x00)))
        goto out;
    if (log && log->fn)
        log->fn(log->ctx, PLUTO_INFO, "uploading firmware\n");
    /* nCONFIG (nInit) low, then high: the FPGA clears itself */
    for (i = 0; i < 4 && !r; i++)
        r = epp_control_write(port, 0x00);
    if (!r)
        r = epp_delay(port, 2000);
    for (i = 0; i < 20 && !r; i++)
        r = epp_control_write(port, 0x04);
    if (!r)
        r = epp_delay(port, 10000);
    if (r)
        goto out;
    for (size_t k = 0; k < len; k++) {
        uint8_t byte = image[k];
        for (int bit = 0; bit < 8; bit++) {
            if ((r = epp_spp_data_write(port, (byte >> bit) & 1 ? 0xFF : 0x00)) ||
                (r = epp_control_write(port, 0x04)) || (r = epp_control_write(port, 0x05)) ||
                (r = epp_control_write(port, 0x04)))
                goto out;
        }
        if ((k + 1) % UPLOAD_CHUNK == 0 && (r = epp_flush(port)))
            goto out;
    }
    if (log && log->fn)
        log->fn(log->ctx, PLUTO_INFO, "done\n");
    if (port->has_ecr && (r = epp_ecr_write(port, 0x80)))
        goto out;
    r = epp_flush(port);
out:
    if (r) {
        epp_discard(port);
        if (log && log->fn)
            log->fn(log->ctx, PLUTO_ERR, "%s: firmware upload failed: %s\n", port->name,
                    strerror(-r));
    }
    return r;
}

int pluto_probe(epp_port_t *port, const char *board, const struct pluto_log *log)
{
    uint8_t b = 0;
    int r = epp_clear_timeout_pluto(port);
    if (!r)
        r = epp_addr_write(port, 0);
    if (!r)
        r = epp_data_read(port, &b, 1);
    if (!r)
        r = epp_timeout(port);
    if (r < 0) {
        if (log && log->fn)
            log->fn(log->ctx, PLUTO_ERR, "%s: port error while probing the %s board: %s\n",
                    port->name, board, strerror(-r));
        return r;
    }
    if (r == 1) {
        if (log && log->fn)
            log->fn(log->ctx, PLUTO_ERR,
                    "Failed to communicate with %s board after programming firmware.\n", board);
        epp_clear_timeout_pluto(port);
        epp_flush(port);
        return -EIO;
    }
    return 0;
}

int pluto_read_firmware(const char *name, uint8_t **buf, size_t *len, char *path_out,
                        size_t path_len, char *err, size_t errlen)
{
    char search[1024];
    int r;
    if (!name || !*name) {
        snprintf(err, errlen, "no firmware file given");
        return -EINVAL;
    }
    if (name[0] == '/') {
        snprintf(path_out, path_len, "%s", name);
    } else {
        const char *sp = hm2_firmware_default_path(search, sizeof(search));
        r = hm2_firmware_find(sp, name, path_out, path_len);
        if (r) {
            snprintf(err, errlen, "firmware '%s' not found (searched %s)", name, sp);
            return r;
        }
    }
    r = hm2_read_file(path_out, PLUTO_FIRMWARE_MAX + 1, buf, len);
    if (r) {
        snprintf(err, errlen, "cannot read firmware file %s: %s", path_out, strerror(-r));
        return r;
    }
    if (*len == 0 || *len > PLUTO_FIRMWARE_MAX) {
        snprintf(err, errlen, "firmware file %s has %zu bytes (expected 1..%u)", path_out, *len,
                 PLUTO_FIRMWARE_MAX);
        free(*buf);
        *buf = NULL;
        return -EINVAL;
    }
    return 0;
}

static void transfer_failed(epp_port_t *p, volatile uint32_t *comm_error,
                            const struct pluto_log *log, const char *board, const char *what,
                            int r)
{
    (*comm_error)++;
    if (log && log->fn)
        log->fn(log->ctx, PLUTO_ERR, "%s: %s on %s failed: error %d\n", board, what, p->name, r);
}

void pluto_write_transfer(epp_port_t *p, const uint8_t *w, const uint8_t *sizes, int n,
                          volatile uint32_t *comm_error, const struct pluto_log *log,
                          const char *board)
{
    int r = epp_addr_write(p, 0);
    for (int k = 0; k < n && !r; k++) {
        r = epp_data_write(p, w, sizes[k]);
        w += sizes[k];
    }
    if (!r)
        r = epp_flush(p);
    if (r)
        transfer_failed(p, comm_error, log, board, "write", r);
}

int pluto_read_transfer(epp_port_t *p, uint8_t rbuf[20], uint8_t *status,
                        volatile uint32_t *comm_error, const struct pluto_log *log,
                        const char *board)
{
    int batching = p->backend->batching;
    int was_error = *comm_error != 0;
    int r = epp_addr_write(p, 0);
    if (!r)
        r = epp_data_read(p, rbuf, 4);
    if (!r)
        r = epp_status_read(p, status);
    if (!r && batching && !was_error)
        r = epp_data_read(p, rbuf + 4, 16);
    if (!r)
        r = epp_flush(p);
    if (r) {
        transfer_failed(p, comm_error, log, board, "read", r);
        return 0;
    }
    if (*status & EPP_STATUS_TIMEOUT) {
        (*comm_error)++;
        epp_clear_timeout_pluto(p);
        epp_flush(p);
    }
    if (*comm_error)
        return 0;
    if (!batching && ((r = epp_data_read(p, rbuf + 4, 16)) || (r = epp_flush(p)))) {
        (*comm_error)++;
        return 0;
    }
    return 1;
}
