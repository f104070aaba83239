/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_7i43 - HAL board driver for the Mesa 7i43 (EPP) with HostMot2
 * firmware (docs/hm2_7i43.md, spec/hostmot2.md §17.2).  loadrt arguments
 * as LinuxCNC's (ioaddr, ioaddr_hi, epp_wide, config, debug_epp), plus
 * port= to choose another epp_port backend per board.
 *
 * Compiled a second time with HM2_EPP_7I90 defined it is hm2_7i90, the
 * driver of the Mesa 7i90 (docs/hm2_7i90.md): the same arguments and
 * transfers, a board whose FPGA loads its firmware from its own flash.
 */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hal.h"
#include "hm2/hostmot2.h"
#include "hm2_board_module.h"
#include "hm2_7i43_llio.h"
#include "rtapi.h"

#ifdef HM2_EPP_7I90
#define DRV "hm2_7i90"
#define BOARD_TEXT "7i90"
#define DRV_VERSION "0.1"
#define setup_board hm2_7i90_setup_board
#else
#define DRV "hm2_7i43"
#define BOARD_TEXT "7i43"
#define DRV_VERSION HM2_7I43_VERSION
#define setup_board hm2_7i43_setup_board
#endif

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("HostMot2 Mesa " BOARD_TEXT " low-level driver (EPP)");

#define NB HM2_7I43_MAX_BOARDS

static int ioaddr[NB] = {0, -1, -1, -1};
RTAPI_MP_ARRAY_INT(ioaddr, NB, "base address of the parallel port(s) (see " DRV "(9) manpage)");
static int ioaddr_hi[NB] = {0, 0, 0, 0};
RTAPI_MP_ARRAY_INT(ioaddr_hi, NB,
                   "secondary address of the parallel port(s) (see " DRV "(9) manpage)");
static int epp_wide[NB] = {1, 1, 1, 1};
RTAPI_MP_ARRAY_INT(epp_wide, NB, "set to 0 to disable wide EPP mode (see (" DRV "(9) manpage)");
static char *config[NB];
RTAPI_MP_ARRAY_STRING(config, NB,
                      "config string(s) for the " BOARD_TEXT " board(s) (see hostmot2(9) manpage)");
static int debug_epp[NB] = {0, 0, 0, 0};
RTAPI_MP_ARRAY_INT(debug_epp, NB, "Developer/debug use only!  Enable debug logging of most EPP\n"
                                  "transfers.");
static char *port[NB];
RTAPI_MP_ARRAY_STRING(port, NB, "epp_port per board: raw:ADDR, ppdev:DEV, gpiod:CHIP:LINES, "
                                "sim:SOCKET (overrides ioaddr)");

struct h7_slot {
    struct hm2_7i43 board;
    epp_port_t port;
    int port_open;
    int registered;
};
/* The module's boards (rtapi_app_exit finds them again here). */
static struct hm2_board_module mod = {NULL, -1};

static void h7_log(int level, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (level == H7_PRINT) {
        char buf[512];
        vsnprintf(buf, sizeof(buf), fmt, ap);
        rtapi_print("%s", buf);
    } else {
        rtapi_vprint_msg(level == H7_ERR    ? RTAPI_MSG_ERR
                         : level == H7_INFO ? RTAPI_MSG_INFO
                                            : RTAPI_MSG_DBG,
                         fmt, ap);
    }
    va_end(ap);
}

static long long h7_now(void)
{
    return rtapi_get_time();
}

static void release_one(void *slots, int i)
{
    struct h7_slot *s = &((struct h7_slot *)slots)[i];
    if (s->registered) {
        rtapi_print("%s: releasing board\n", s->board.llio.name);
        hm2_unregister(&s->board.llio);
    }
    if (s->port_open)
        epp_port_close(&s->port);
}

static int board_wanted(int i)
{
    return (port[i] && port[i][0]) || ioaddr[i] >= 0;
}

static int setup_one(void *slots, int i, int comp_id)
{
    struct h7_slot *s = &((struct h7_slot *)slots)[i];
    char err[640];
    int r = epp_port_open(&s->port, port[i], ioaddr[i], ioaddr_hi[i], epp_wide[i], err,
                          sizeof(err));
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, DRV ": board %d: cannot open the parallel port: %s\n", i,
                        err);
        return r;
    }
    s->port_open = 1;
    r = setup_board(&s->board, &s->port, i, epp_wide[i], debug_epp[i], h7_log, h7_now);
    unsigned lo = (unsigned)s->port.base, hi = (unsigned)s->port.base_hi;
    if (!r) {
        s->board.llio.comp_id = comp_id;
        r = hm2_register(&s->board.llio, config[i]);
    }
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "%s: board at (ioaddr=0x%04X, ioaddr_hi=0x%04X, epp_wide %s) not found!\n",
                        s->board.llio.name[0] ? s->board.llio.name : DRV, lo, hi,
                        s->board.epp_wide ? "ON" : "OFF");
        return r;
    }
    s->registered = 1;
    rtapi_print("%s: board at (ioaddr=0x%04X, ioaddr_hi=0x%04X, epp_wide %s) found\n",
                s->board.llio.name, lo, hi, s->board.epp_wide ? "ON" : "OFF");
    if (s->port.backend && strcmp(s->port.backend->kind, "raw") != 0)
        rtapi_print_msg(RTAPI_MSG_INFO, "%s: on port %s\n", s->board.llio.name, s->port.name);
    return 0;
}

static const struct hm2_board_module_desc desc = {
    .name = DRV,
    .none_given = "no boards given (ioaddr[0] < 0 and no port)",
    .max_boards = NB, .slot_size = sizeof(struct h7_slot),
    .wanted = board_wanted, .setup = setup_one, .release = release_one,
};

int rtapi_app_main(void)
{
    rtapi_print(DRV ": loading HostMot2 Mesa " BOARD_TEXT " driver version " DRV_VERSION "\n");
    return hm2_board_module_load(&mod, &desc);
}

void rtapi_app_exit(void)
{
    hm2_board_module_unload(&mod, &desc);
}
