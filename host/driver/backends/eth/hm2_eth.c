/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_eth - HAL board driver for Mesa Ethernet Anything-I/O boards (7i92,
 * 7i96, 7i96S) with HostMot2 firmware, over LBP16/UDP (docs/hm2_eth.md,
 * spec/hostmot2.md 17.3).  loadrt arguments as LinuxCNC's:
 *
 *   loadrt hostmot2
 *   loadrt hm2_eth board_ip=192.168.1.121[,10.10.10.10] config="num_encoders=1"
 *
 * Besides the hostmot2 pins each board gets packet-error, packet-error-level,
 * packet-error-exceeded, packet-error-total pins and the packet-error-limit,
 * -increment, -decrement and packet-read-timeout parameters.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "hal.h"
#include "hm2/hostmot2.h"
#include "hm2_board_module.h"
#include "hm2_eth_llio.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("Driver for HostMot2 on Mesa Ethernet Anything-I/O boards (LBP16 over UDP)");

#define NB HM2_ETH_MAX_BOARDS

static char *board_ip[NB];
RTAPI_MP_ARRAY_STRING(board_ip, NB, "ip address of ethernet board(s)");
static char *config[NB];
RTAPI_MP_ARRAY_STRING(config, NB, "config string for the AnyIO boards (see hostmot2(9) manpage)");
static int debug = 0;
RTAPI_MP_INT(debug, "Developer/debug use only!  Enable debug logging.");

struct he_slot {
    struct hm2_eth_board board;
    int set_up;
    int registered;
};

/* The module's boards (rtapi_app_exit finds them again here). */
static struct hm2_board_module mod = {NULL, -1};

static void he_log(void *ctx, int level, const char *line)
{
    if (level >= HM2_DBG && debug)
        level = HM2_ERR;
    hm2_board_rtapi_log(ctx, level, line);
}

static void release_one(void *slots, int i)
{
    struct he_slot *s = &((struct he_slot *)slots)[i];
    if (s->registered)
        hm2_unregister(&s->board.llio);
    if (s->set_up)
        hm2_eth_teardown(&s->board, false);
}

static int board_wanted(int i)
{
    return board_ip[i] && board_ip[i][0];
}

/* hm2_<board>.<n>: n counts the boards of the same type */
static int type_index(const struct he_slot *slots, int i)
{
    int n = 0;
    for (int j = 0; j < i; j++)
        if (slots[j].set_up && slots[j].board.info == slots[i].board.info)
            n++;
    return n;
}

/* The packet-error pins and parameters: pointers and values in HAL memory. */
struct he_hal {
    struct hm2_eth_errpins p; /* the pin pointers: HAL links update them here */
    hal_s32_t limit, increment, decrement, read_timeout;
};

static int export_errpins(struct hm2_eth_board *b, int comp_id)
{
    const char *n = b->llio.name;
    struct he_hal *h = hal_malloc(sizeof(*h));
    if (!h) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: out of HAL memory for the packet-error pins\n", n);
        return -ENOMEM;
    }
    h->limit = b->local.limit;
    h->increment = b->local.increment;
    h->decrement = b->local.decrement;
    h->read_timeout = b->local.read_timeout;
    int r;
    if ((r = hal_pin_bit_newf(HAL_OUT, &h->p.error, comp_id, "%s.packet-error", n)) ||
        (r = hal_pin_s32_newf(HAL_OUT, &h->p.level, comp_id, "%s.packet-error-level", n)) ||
        (r = hal_pin_bit_newf(HAL_OUT, &h->p.exceeded, comp_id, "%s.packet-error-exceeded", n)) ||
        (r = hal_pin_u32_newf(HAL_IO, &h->p.total, comp_id, "%s.packet-error-total", n)) ||
        (r = hal_param_s32_newf(HAL_RW, &h->read_timeout, comp_id, "%s.packet-read-timeout",
                                n)) ||
        (r = hal_param_s32_newf(HAL_RW, &h->limit, comp_id, "%s.packet-error-limit", n)) ||
        (r = hal_param_s32_newf(HAL_RW, &h->increment, comp_id, "%s.packet-error-increment",
                                n)) ||
        (r = hal_param_s32_newf(HAL_RW, &h->decrement, comp_id, "%s.packet-error-decrement",
                                n))) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: cannot export the packet-error pins: %s\n", n,
                        strerror(-r));
        return r;
    }
    h->p.limit = &h->limit;
    h->p.increment = &h->increment;
    h->p.decrement = &h->decrement;
    h->p.read_timeout = &h->read_timeout;
    *h->p.error = false;
    *h->p.exceeded = false;
    *h->p.level = 0;
    *h->p.total = 0;
    b->pins = &h->p;
    return 0;
}

static int setup_one(void *slots, int i, int comp_id)
{
    struct he_slot *s = &((struct he_slot *)slots)[i];
    int r = hm2_eth_setup(&s->board, board_ip[i], 0, he_log, NULL);
    if (r)
        return r;
    s->set_up = 1;
    hm2_board_fill_llio(s->board.info, type_index(slots, i), &s->board.llio);
    s->board.llio.comp_id = comp_id;
    r = export_errpins(&s->board, comp_id);
    if (r)
        return r;
    r = hm2_register(&s->board.llio, config[i]);
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_eth: %s: board at %s fails HM2 registration\n",
                        s->board.llio.name, board_ip[i]);
        return r;
    }
    s->registered = 1;
    return 0;
}

static const struct hm2_board_module_desc desc = {
    .name = "hm2_eth",
    .none_given = "no board_ip given (board_ip=192.168.1.121[,IP...])",
    .max_boards = NB, .slot_size = sizeof(struct he_slot),
    .wanted = board_wanted, .setup = setup_one, .release = release_one,
};

int rtapi_app_main(void)
{
    rtapi_print("hm2_eth: loading Mesa AnyIO HostMot2 ethernet driver version 0.2\n");
    return hm2_board_module_load(&mod, &desc);
}

void rtapi_app_exit(void)
{
    hm2_board_module_unload(&mod, &desc);
}
