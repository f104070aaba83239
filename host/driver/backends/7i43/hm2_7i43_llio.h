/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_7i43_llio.h - the Mesa 7i43 (and 7i90) as an hm2 llio on an epp_port
 * (spec/hostmot2.md §17.2, §18; docs/hm2_7i43.md).  No HAL calls: the RT
 * module (hm2_7i43.c) and the unit tests both use it.
 */
#ifndef HM2_7I43_LLIO_H
#define HM2_7I43_LLIO_H

#include <stdint.h>

#include "hm2/epp_port.h"
#include "hm2/llio.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_7I43_VERSION "0.3"
#define HM2_7I43_MAX_BOARDS 4
#define HM2_7I43_ADDR_AUTOINCREMENT 0x8000u
#define HM2_7I43_MAX_QUEUE 128

/* Message levels: what the log function gets. */
enum { H7_PRINT = 0, H7_ERR = 1, H7_INFO = 3, H7_DBG = 4 };
typedef void (*h7_log_fn)(int level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Current time in ns (rtapi_get_time in the module). */
typedef long long (*h7_time_fn)(void);

struct h7_xfer {
    uint32_t addr;
    uint32_t size;
    uint8_t status;
};

struct hm2_7i43 {
    hm2_llio_t llio;
    char drv[16]; /* "hm2_7i43", "hm2_7i90": the driver's message prefix */
    epp_port_t *port;
    int epp_wide;
    int debug_epp;
    h7_log_fn log;
    h7_time_fn now;
    struct h7_xfer qr[HM2_7I43_MAX_QUEUE], qw[HM2_7I43_MAX_QUEUE];
    int nqr, nqw;
};

/* Prepare the port (ECR 0x94 when present, control 0x04, clear timeout),
 * fill the llio (name hm2_7i43.<index>, board-table geometry), reset the
 * FPGA through the CPLD and detect its size (3s200tq144 / 3s400tq144).
 * 0 or -errno after printing why. */
int hm2_7i43_setup_board(struct hm2_7i43 *b, epp_port_t *port, int index, int epp_wide,
                         int debug_epp, h7_log_fn log, h7_time_fn now);

/* The Mesa 7i90 (EPP, firmware in its own flash): the same port setup and
 * register transfers, llio hm2_7i90.<index>, no reset and no programming.
 * 0 or -errno after printing why. */
int hm2_7i90_setup_board(struct hm2_7i43 *b, epp_port_t *port, int index, int epp_wide,
                         int debug_epp, h7_log_fn log, h7_time_fn now);

/* The llio functions (also reachable through b->llio). */
int hm2_7i43_read(hm2_llio_t *llio, uint32_t addr, void *buffer, size_t size);
int hm2_7i43_write(hm2_llio_t *llio, uint32_t addr, const void *buffer, size_t size);
int hm2_7i43_reset(hm2_llio_t *llio);

#ifdef __cplusplus
}
#endif

#endif /* HM2_7I43_LLIO_H */
