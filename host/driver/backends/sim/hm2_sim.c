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
 *
 * With inproc=1 the boards run inside this process instead
 * (lib/libvboard_inproc.so, loaded here): board[i] names board i,
 * firmware[i] its built-in firmware (or config's firmware= programs it),
 * loops[i] its pin loops; a servo period's reads and writes are calls.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "hal.h"
#include "hm2/hostmot2.h"
#include "hm2_board_module.h"
#include "hm2_sim_inproc.h"
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
RTAPI_MP_ARRAY_STRING(board, NB, "board of each socket (5i20, ...; optional: checked when "
                                  "given), or of each in-process board (inproc=1)");
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
static int inproc = 0;
RTAPI_MP_INT(inproc, "1: run the boards inside this process (lib/libvboard_inproc.so) instead of "
                     "talking to bin/vboard sockets");
static char *firmware[NB];
RTAPI_MP_ARRAY_STRING(firmware, NB, "inproc=1: built-in firmware of each board (SVST8_4, ...)");
static int freerun = 0;
RTAPI_MP_INT(freerun, "inproc=1: 1 runs each board free with the wall clock on a thread of its "
                      "own (as vboard --freerun) instead of in lockstep with HAL");
static int stats = 0;
RTAPI_MP_INT(stats, "inproc=1: 1 prints, at unload, where each board's servo periods spent "
                    "their time (board model vs transport)");
static char *loops[NB];
RTAPI_MP_ARRAY_STRING(loops, NB, "inproc=1: pin loops of each board, FROM:TO[:inv] words");

struct hs_slot {
    struct hm2_sim_board board;
    struct hm2_sim_inproc ib;
    int set_up;
    int registered;
};

/* inproc=1: the board library, loaded once for all boards */
static struct hm2_sim_inproc_lib lib;

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

static hm2_llio_t *llio_of(struct hs_slot *s)
{
    return inproc ? &s->ib.llio : &s->board.llio;
}

static const char *where(int i)
{
    return inproc ? "in this process" : sockets[i];
}

static void release_one(void *slots, int i)
{
    struct hs_slot *s = &((struct hs_slot *)slots)[i];
    if (s->registered && inproc && stats)
        hm2_sim_inproc_report(&s->ib);
    if (s->registered) {
        rtapi_print("%s: dropping virtual board %s%s\n", llio_of(s)->name, inproc ? "" : "at ",
                    where(i));
        hm2_unregister(llio_of(s));
    }
    if (s->set_up && inproc)
        hm2_sim_inproc_teardown(&s->ib);
    else if (s->set_up)
        hm2_sim_teardown(&s->board);
}

static int board_wanted(int i)
{
    if (inproc)
        return board[i] && board[i][0];
    return sockets[i] && sockets[i][0];
}

/* hm2_<board>.<n>: n counts the boards of the same type, as hm2_pci does */
static int type_index(const struct hs_slot *slots, int i, const char *name)
{
    int n = 0;
    for (int j = 0; j < i; j++) {
        const char *b = inproc ? slots[j].ib.hello.board : slots[j].board.hello.board;
        if (slots[j].set_up && strcasecmp(b, name) == 0)
            n++;
    }
    return n;
}

static int register_one(struct hs_slot *s, int i, int comp_id, const char *fw)
{
    hm2_llio_t *l = llio_of(s);
    l->comp_id = comp_id;
    int r = hm2_register(l, config[i]);
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: virtual board %s%s fails HM2 registration\n",
                        l->name, inproc ? "" : "at ", where(i));
        return r;
    }
    s->registered = 1;
    rtapi_print("%s: initialized virtual AnyIO board %s%s (%s)\n", l->name,
                inproc ? "" : "at ", where(i),
                fw[0] ? fw : "blank");
    return 0;
}

static int setup_inproc(struct hs_slot *s, int i, int comp_id)
{
    if (sockets[i] && sockets[i][0]) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_sim: inproc=1 runs the boards in this process: "
                                       "socket=%s makes no sense with it\n", sockets[i]);
        return -EINVAL;
    }
    if (host_time && !freerun && !rtapi_is_simclock()) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "hm2_sim: in-process board %d runs in lockstep with HAL's clock but "
                        "this HAL session runs on the wall clock, so the board would fall "
                        "behind real time; run the session on the simulated clock (halrun -S) "
                        "or load with freerun=1 (the board runs with the wall clock) or "
                        "host_time=0 (its clocks stand still)\n", i);
        return -EINVAL;
    }
    int r = hm2_sim_inproc_setup(&s->ib, &lib, board[i], firmware[i], 0,
                                 host_time ? hs_now : hs_no_time, hm2_board_rtapi_log, NULL);
    if (r)
        return r;
    s->set_up = 1;
    s->ib.stats = stats != 0;
    if ((r = hm2_sim_inproc_loops(&s->ib, loops[i])))
        return r;
    if (freerun && (r = hm2_sim_inproc_freerun(&s->ib)))
        return r;
    int index = type_index((const struct hs_slot *)s - i, i, s->ib.hello.board);
    hm2_board_fill_llio(s->ib.info, index, &s->ib.llio);
    return register_one(s, i, comp_id, s->ib.hello.firmware);
}

static int setup_one(void *slots, int i, int comp_id)
{
    struct hs_slot *s = &((struct hs_slot *)slots)[i];
    if (inproc)
        return setup_inproc(s, i, comp_id);
    if ((firmware[i] && firmware[i][0]) || (loops[i] && loops[i][0]) || freerun) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_sim: firmware=, loops= and freerun= are for "
                                       "in-process boards (inproc=1); a socket board takes them "
                                       "on the vboard command line\n");
        return -EINVAL;
    }
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
    return register_one(s, i, comp_id, s->board.hello.firmware);
}

static const struct hm2_board_module_desc desc = {
    .name = "hm2_sim",
    .none_given = "no board given (socket=PATH[,PATH...], or inproc=1 board=NAME[,NAME...])",
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
    if ((inproc != 0 && inproc != 1) || (freerun != 0 && freerun != 1)) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_sim: inproc=%d freerun=%d: want 0 or 1\n", inproc,
                        freerun);
        return -EINVAL;
    }
    if (inproc) {
        int r = hm2_sim_inproc_lib_open(&lib, NULL, hm2_board_rtapi_log, NULL);
        if (r)
            return r;
    }
    int r = hm2_board_module_load(&mod, &desc);
    if (r)
        hm2_sim_inproc_lib_close(&lib);
    return r;
}

void rtapi_app_exit(void)
{
    hm2_board_module_unload(&mod, &desc);
    hm2_sim_inproc_lib_close(&lib);
}
