/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_7i43_llio.c - the 7i43's llio over an epp_port (spec/hostmot2.md
 * §17.2).  Register transfer = address write (addr | 0x8000) low byte,
 * address write high byte, n data cycles (auto-increment), status read:
 * bit 0 set -> "EPP timeout on data cycle of read(addr=0x%04x, size=%d)".
 *
 * Queued transfers keep that exact sequence per transfer, but all of a
 * period's transfers go out in one flush (one round trip to the virtual
 * board); the status of each is checked afterwards, in order.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/bitfile.h"
#include "hm2/boards.h"
#include "hm2_7i43_llio.h"

_Static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
               "hm2_7i43: EPP bytes are copied as host-order words (little-endian hosts only)");

#define COOKIE 0x55AACAFEu

static struct hm2_7i43 *board_of(hm2_llio_t *llio)
{
    return (struct hm2_7i43 *)llio->priv;
}

static int addr16(struct hm2_7i43 *b, uint32_t addr)
{
    int r = epp_addr_write(b->port, (uint8_t)(addr & 0xFF));
    if (!r)
        r = epp_addr_write(b->port, (uint8_t)((addr >> 8) & 0xFF));
    if (!r && b->debug_epp)
        b->log(H7_PRINT, "%s: selected address 0x%04X\n", b->drv, addr & 0xFFFF);
    return r;
}

static int check_size(struct hm2_7i43 *b, const char *what, uint32_t addr, size_t size)
{
    if (size == 0 || size > 0x10000 || addr > 0xFFFF) {
        b->log(H7_ERR, "%s: bad %s(addr=0x%04x, size=%d)\n", b->llio.name, what, addr,
               (int)size);
        return -EINVAL;
    }
    return 0;
}

/* After an EPP timeout: message, clear, fail (the core sets io_error). */
static int timed_out(struct hm2_7i43 *b, const char *what, uint32_t addr, uint32_t size)
{
    b->log(H7_ERR, "%s: EPP timeout on data cycle of %s(addr=0x%04x, size=%d)\n", b->llio.name,
           what, addr, (int)size);
    int r = epp_clear_timeout_hm2(b->port);
    if (r == 1)
        b->log(H7_ERR, "%s: failed to clear EPP Timeout!\n", b->drv);
    return -EIO;
}

static int port_failed(struct hm2_7i43 *b, const char *what, int r)
{
    epp_discard(b->port);
    b->log(H7_ERR, "%s: %s on port %s failed: %s\n", b->llio.name, what, b->port->name,
           strerror(-r));
    return r;
}

static int queue_xfer(struct hm2_7i43 *b, int is_write, uint32_t addr, void *buf, size_t size,
                      uint8_t *status)
{
    int r = addr16(b, addr | HM2_7I43_ADDR_AUTOINCREMENT);
    if (!r)
        r = is_write ? epp_data_write(b->port, buf, size) : epp_data_read(b->port, buf, size);
    if (!r)
        r = epp_status_read(b->port, status);
    return r;
}

int hm2_7i43_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    struct hm2_7i43 *b = board_of(llio);
    uint8_t st = 0;
    int r = check_size(b, "read", addr, size);
    if (r)
        return r;
    r = queue_xfer(b, 0, addr, buffer, size, &st);
    if (!r)
        r = epp_flush(b->port);
    if (r)
        return port_failed(b, "read", r);
    if (st & EPP_STATUS_TIMEOUT)
        return timed_out(b, "read", addr, (uint32_t)size);
    if (b->debug_epp)
        for (size_t i = 0; i + 4 <= size; i += 4) {
            uint32_t v;
            memcpy(&v, (uint8_t *)buffer + i, 4);
            b->log(H7_PRINT, "%s: read data 0x%08X\n", b->drv, v);
        }
    return 0;
}

int hm2_7i43_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    struct hm2_7i43 *b = board_of(llio);
    uint8_t st = 0;
    int r = check_size(b, "write", addr, size);
    if (r)
        return r;
    if (b->debug_epp)
        for (size_t i = 0; i + 4 <= size; i += 4) {
            uint32_t v;
            memcpy(&v, (const uint8_t *)buffer + i, 4);
            b->log(H7_PRINT, "%s: wrote data 0x%08X\n", b->drv, v);
        }
    r = queue_xfer(b, 1, addr, (void *)buffer, size, &st);
    if (!r)
        r = epp_flush(b->port);
    if (r)
        return port_failed(b, "write", r);
    if (st & EPP_STATUS_TIMEOUT)
        return timed_out(b, "write", addr, (uint32_t)size);
    return 0;
}

/* ---- queued transfers --------------------------------------------------- */

static int queue_common(struct hm2_7i43 *b, int is_write, uint32_t addr, void *buf, size_t size)
{
    struct h7_xfer *q = is_write ? b->qw : b->qr;
    int *n = is_write ? &b->nqw : &b->nqr;
    int r = check_size(b, is_write ? "queue_write" : "queue_read", addr, size);
    if (!r && *n >= HM2_7I43_MAX_QUEUE) {
        b->log(H7_ERR, "%s: %s queue full (%d transfers)\n", b->llio.name,
               is_write ? "write" : "read", HM2_7I43_MAX_QUEUE);
        r = -ENOSPC;
    }
    /* one port queue holds both directions: a read queue and a write queue
     * must not be open at the same time (the core never does that) */
    if (!r && (is_write ? b->nqr : b->nqw)) {
        b->log(H7_ERR, "%s: read and write queued at the same time\n", b->llio.name);
        r = -EINVAL;
    }
    if (!r) {
        q[*n].addr = addr;
        q[*n].size = (uint32_t)size;
        q[*n].status = 0;
        r = queue_xfer(b, is_write, addr, buf, size, &q[*n].status);
        if (r)
            b->log(H7_ERR, "%s: cannot queue a transfer on %s: %s\n", b->llio.name,
                   b->port->name, strerror(-r));
    }
    if (r) {
        epp_discard(b->port);
        b->nqr = b->nqw = 0;
        return r;
    }
    (*n)++;
    return 0;
}

static int send_common(struct hm2_7i43 *b, int is_write)
{
    struct h7_xfer *q = is_write ? b->qw : b->qr;
    int *n = is_write ? &b->nqw : &b->nqr;
    int count = *n;
    *n = 0;
    int r = epp_flush(b->port);
    if (r)
        return port_failed(b, is_write ? "queued write" : "queued read", r);
    for (int i = 0; i < count; i++)
        if (q[i].status & EPP_STATUS_TIMEOUT)
            return timed_out(b, is_write ? "write" : "read", q[i].addr, q[i].size);
    return 0;
}

static int h7_queue_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size)
{
    return queue_common(board_of(llio), 0, addr, buffer, size);
}

static int h7_send_queued_reads(hm2_llio_t *llio)
{
    return send_common(board_of(llio), 0);
}

static int h7_queue_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size)
{
    return queue_common(board_of(llio), 1, addr, (void *)buffer, size);
}

static int h7_send_queued_writes(hm2_llio_t *llio)
{
    return send_common(board_of(llio), 1);
}

/* ---- CPLD: reset, size, programming ------------------------------------ */

static int cpld_byte_write(struct hm2_7i43 *b, uint8_t v)
{
    return epp_data_write8(b->port, &v, 1);
}

int hm2_7i43_reset(hm2_llio_t *llio)
{
    struct hm2_7i43 *b = board_of(llio);
    uint8_t done = 0;
    int r;
    /* A configured hm2 FPGA reconfigures on 0x5A at 0x7F7F; the CPLD takes
     * the same cycles harmlessly (control register, PROG_B low). */
    if ((r = addr16(b, 0x7F7F)) || (r = cpld_byte_write(b, 0x5A)) || (r = addr16(b, 0x7F7F)) ||
        (r = cpld_byte_write(b, 0x5A)))
        goto fail;
    /* CPLD control register: PROG_B low >= 300 ns, then high, 2 ms */
    if ((r = epp_addr_write(b->port, 1)) || (r = cpld_byte_write(b, 0x00)) ||
        (r = epp_delay(b->port, 1000)) || (r = cpld_byte_write(b, 0x01)) ||
        (r = epp_delay(b->port, 2000000)))
        goto fail;
    if ((r = epp_data_read(b->port, &done, 1)) || (r = epp_flush(b->port)))
        goto fail;
    if (done & 0x01) {
        b->log(H7_PRINT, "hm2_7i43: /DONE is not low after CPLD reset!\n");
        return -EIO;
    }
    return 0;
fail:
    return port_failed(b, "CPLD reset", r);
}

static int detect_size(struct hm2_7i43 *b)
{
    uint8_t v = 0;
    int r = epp_addr_write(b->port, 0);
    if (!r)
        r = epp_data_read(b->port, &v, 1);
    if (!r)
        r = epp_flush(b->port);
    if (r)
        return port_failed(b, "FPGA size detection", r);
    b->llio.fpga_part_number = (v & 0x01) ? "3s400tq144" : "3s200tq144";
    b->log(H7_DBG, "%s: detected FPGA '%s'\n", b->llio.name, b->llio.fpga_part_number);
    return 0;
}

static int h7_program_fpga(hm2_llio_t *llio, const struct hm2_bitfile *bf)
{
    struct hm2_7i43 *b = board_of(llio);
    uint8_t *rev = malloc(bf->size ? bf->size : 1);
    int r, t;
    if (!rev) {
        b->log(H7_ERR, "%s: out of memory for the %u-byte bitstream\n", llio->name, bf->size);
        return -ENOMEM;
    }
    for (uint32_t i = 0; i < bf->size; i++)
        rev[i] = hm2_bitfile_reverse(bf->data[i]);
    long long start = b->now();
    r = epp_addr_write(b->port, 0);
    if (!r)
        r = epp_data_write8(b->port, rev, bf->size);
    if (!r)
        r = epp_flush(b->port);
    long long end = b->now();
    free(rev);
    if (r)
        return port_failed(b, "sending firmware", r);
    t = epp_timeout(b->port);
    if (t < 0)
        return port_failed(b, "sending firmware", t);
    if (t) {
        b->log(H7_PRINT, "%s: EPP Timeout while sending firmware!\n", llio->name);
        epp_clear_timeout_hm2(b->port);
        return -EIO;
    }
    if (end > start) {
        double secs = (double)(end - start) / 1e9;
        b->log(H7_INFO, "%s: %u bytes of firmware sent (%u KB/s)\n", llio->name, bf->size,
               (unsigned)((double)bf->size / secs / 1024.0));
    }
    if (b->port->wide) {
        /* some ports do not do 32-bit EPP right: check, fall back to bytes */
        uint32_t cookie = 0;
        r = hm2_7i43_read(llio, 0x100, &cookie, 4);
        if (r && r != -EIO)
            return r;
        if (r == -EIO || cookie != COOKIE) {
            b->log(H7_PRINT,
                   "%s: Reading cookie with epp_wide failed. (read 0x%08x) Falling back to "
                   "byte transfers\n",
                   llio->name, cookie);
            b->port->wide = 0;
            b->epp_wide = 0;
            cookie = 0;
            r = hm2_7i43_read(llio, 0x100, &cookie, 4);
            if (r && r != -EIO)
                return r;
            if (r == 0 && cookie == COOKIE)
                b->log(H7_PRINT, "%s: Successfully read cookie after selecting byte transfers\n",
                       llio->name);
            else
                b->log(H7_PRINT,
                       "%s: Reading cookie still failed without epp_wide. (read 0x%08x)\n",
                       llio->name, cookie);
        }
    }
    return 0;
}

/* What both EPP boards do: the llio from the board table, the port in EPP
 * mode with its control lines idle and no stale timeout. */
static int epp_board_setup(struct hm2_7i43 *b, const char *board, epp_port_t *port, int index,
                           int epp_wide, int debug_epp, h7_log_fn log, h7_time_fn now)
{
    const struct hm2_board_info *info = hm2_board_lookup(board);
    int r;
    memset(b, 0, sizeof(*b));
    snprintf(b->drv, sizeof(b->drv), "hm2_%s", board);
    b->port = port;
    b->epp_wide = epp_wide ? 1 : 0;
    b->debug_epp = debug_epp;
    b->log = log;
    b->now = now;
    port->wide = b->epp_wide;
    if (!info) {
        log(H7_ERR, "%s: board table has no %s\n", b->drv, board);
        return -EINVAL;
    }
    hm2_board_fill_llio(info, index, &b->llio);
    b->llio.threadsafe = 0;
    b->llio.read = hm2_7i43_read;
    b->llio.write = hm2_7i43_write;
    b->llio.queue_read = h7_queue_read;
    b->llio.send_queued_reads = h7_send_queued_reads;
    b->llio.queue_write = h7_queue_write;
    b->llio.send_queued_writes = h7_send_queued_writes;
    b->llio.priv = b;

    /* EPP mode in the ECR, control lines idle, no stale timeout */
    r = port->has_ecr ? epp_ecr_write(port, 0x94) : 0;
    if (!r)
        r = epp_control_write(port, 0x04);
    if (!r)
        r = epp_flush(port);
    if (r)
        return port_failed(b, "port setup", r);
    r = epp_clear_timeout_hm2(port);
    if (r < 0)
        return port_failed(b, "port setup", r);
    if (r == 1)
        log(H7_ERR, "%s: failed to clear EPP Timeout!\n", b->drv);
    return 0;
}

int hm2_7i43_setup_board(struct hm2_7i43 *b, epp_port_t *port, int index, int epp_wide,
                         int debug_epp, h7_log_fn log, h7_time_fn now)
{
    int r = epp_board_setup(b, "7i43", port, index, epp_wide, debug_epp, log, now);
    if (r)
        return r;
    b->llio.reset = hm2_7i43_reset;
    b->llio.program_fpga = h7_program_fpga;
    r = hm2_7i43_reset(&b->llio);
    if (r)
        return r;
    return detect_size(b);
}

int hm2_7i90_setup_board(struct hm2_7i43 *b, epp_port_t *port, int index, int epp_wide,
                         int debug_epp, h7_log_fn log, h7_time_fn now)
{
    /* the FPGA configures itself from the board's flash: no reset, no
     * programming (a config firmware= is ignored), the part is the table's */
    return epp_board_setup(b, "7i90", port, index, epp_wide, debug_epp, log, now);
}
