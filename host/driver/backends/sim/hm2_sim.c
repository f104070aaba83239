/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_sim - HAL board driver for virtual HostMot2 local-bus boards
 * (bin/vboard, docs/hm2_sim.md).  As hm2_pci takes boards by PCI address
 * and hm2_7i43 by EPP address, hm2_sim takes them by socket path:
 *
 *   loadrt hostmot2
 *   loadrt hm2_sim socket=/tmp/b0.sock[,/tmp/b1.sock] board=5i20[,5i20]
 *                  config="firmware=hm2/5i20/SVST8_4.BIT num_encoders=1"
 *
 * board[i] is optional (the virtual board says what it is); when given it
 * must match.  config[i] is the hostmot2 config string of board i.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "hal.h"
#include "hm2/hostmot2.h"
#include "hm2_board_module.h"
#include "hm2_sim_llio.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("Driver for HostMot2 on virtual Anything-I/O boards (bin/vboard sockets)");

#define NB HM2_SIM_MAX_BOARDS

/* Parameter "socket": the variable cannot be called socket (the static
 * client in this module calls libc's socket()), so its RTAPI symbols are
 * spelled out instead of using RTAPI_MP_ARRAY_STRING. */
static char *sockets[NB];
RTAPI_EXPORT __attribute__((used)) void *rtapi_info_address_socket = (void *)&sockets;
RTAPI_EXPORT __attribute__((used)) const char *rtapi_info_type_socket = RTAPI_MP_TYPE_STRING;
RTAPI_EXPORT __attribute__((used)) const char *rtapi_info_description_socket =
    "socket path of each virtual board (bin/vboard --socket)";
RTAPI_EXPORT __attribute__((used)) int rtapi_info_size_socket = NB;
static char *board[NB];
RTAPI_MP_ARRAY_STRING(board, NB, "expected board of each socket (5i20, ...; optional)");
static char *config[NB];
RTAPI_MP_ARRAY_STRING(config, NB, "config string for the boards (see hostmot2(9) manpage)");
static int host_time = 1;
RTAPI_MP_INT(host_time, "1: requests carry rtapi_get_time() (board in lockstep with HAL); 0: they "
                        "carry 0 and never advance the board's clock");
static int async_writes = 0;
RTAPI_MP_INT(async_writes, "1: send each period's writes without waiting for the board's reply "
                           "(checked with the next request; one round trip per period)");
static int spin_us = 0;
RTAPI_MP_INT(spin_us, "busy-wait up to this many us for each board reply before sleeping");

struct hs_slot {
    struct hm2_sim_board board;
    int set_up;
    int registered;
};

/* The module's boards (rtapi_app_exit finds them again here). */
static struct hm2_board_module mod = {NULL, -1};

static int64_t hs_now(void)
{
    return (int64_t)rtapi_get_time();
}

static int64_t hs_no_time(void)
{
    return 0;
}

static void release_one(void *slots, int i)
{
    struct hs_slot *s = &((struct hs_slot *)slots)[i];
    if (s->registered) {
        rtapi_print("%s: dropping virtual board at %s\n", s->board.llio.name, sockets[i]);
        hm2_unregister(&s->board.llio);
    }
    if (s->set_up)
        hm2_sim_teardown(&s->board);
}

static int board_wanted(int i)
{
    return sockets[i] && sockets[i][0];
}

/* hm2_<board>.<n>: n counts the boards of the same type, as hm2_pci does */
static int type_index(const struct hs_slot *slots, int i, const char *name)
{
    int n = 0;
    for (int j = 0; j < i; j++)
        if (slots[j].set_up && strcasecmp(slots[j].board.hello.board, name) == 0)
            n++;
    return n;
}

static int setup_one(void *slots, int i, int comp_id)
{
    struct hs_slot *s = &((struct hs_slot *)slots)[i];
    /* the index depends on the board type, which only HELLO tells: set up
     * with index 0, then rename */
    int r = hm2_sim_setup(&s->board, sockets[i], board[i], 0, host_time ? hs_now : hs_no_time,
                          hm2_board_rtapi_log, NULL);
    if (r)
        return r;
    s->set_up = 1;
    if (host_time && vbc_check_clock(&s->board.vbc, &s->board.hello, rtapi_is_simclock())) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_sim: %s\n", s->board.vbc.err);
        return -EINVAL;
    }
    s->board.vbc.spin_us = spin_us;
    s->board.async_writes = async_writes != 0;
    int index = type_index(slots, i, s->board.hello.board);
    hm2_board_fill_llio(s->board.info, index, &s->board.llio);
    s->board.llio.comp_id = comp_id;
    r = hm2_register(&s->board.llio, config[i]);
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: virtual board at %s fails HM2 registration\n",
                        s->board.llio.name, sockets[i]);
        return r;
    }
    s->registered = 1;
    rtapi_print("%s: initialized virtual AnyIO board at %s (%s)\n", s->board.llio.name, sockets[i],
                s->board.hello.firmware[0] ? s->board.hello.firmware : "blank");
    return 0;
}

static const struct hm2_board_module_desc desc = {
    .name = "hm2_sim",
    .none_given = "no board given (socket=PATH[,PATH...])",
    .max_boards = NB, .slot_size = sizeof(struct hs_slot),
    .wanted = board_wanted, .setup = setup_one, .release = release_one,
};

int rtapi_app_main(void)
{
    rtapi_print("hm2_sim: loading HostMot2 virtual board driver\n");
    if (spin_us < 0 || spin_us > 10000) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_sim: spin_us=%d out of range (0..10000)\n", spin_us);
        return -EINVAL;
    }
    return hm2_board_module_load(&mod, &desc);
}

void rtapi_app_exit(void)
{
    hm2_board_module_unload(&mod, &desc);
}
