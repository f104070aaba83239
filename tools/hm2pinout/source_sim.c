/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2pinout's sim: source: a virtual board (bin/vboard) reached through its
 * socket with the hm2_sim backend's llio.  The board is never reset or
 * programmed and its clocks are not advanced (every request carries host
 * time 0): the report is of the firmware it runs now.
 *   sim:/tmp/board.sock
 */
#define _GNU_SOURCE
#include "source_sim.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "hm2_sim_llio.h"

static void sim_log(void *ctx, int level, const char *line)
{
    (void)ctx;
    if (level == HM2_ERR || level == HM2_WARN)
        fprintf(stderr, "hm2pinout: %s\n", line);
}

int hm2pinout_open_sim(const char *path, int index, hm2_llio_t **llio, void **handle)
{
    struct hm2_sim_board *sb = calloc(1, sizeof(*sb));
    if (!sb) {
        fprintf(stderr, "hm2pinout: out of memory\n");
        return -ENOMEM;
    }
    int r = hm2_sim_setup(sb, path, NULL, index, NULL, sim_log, NULL);
    if (r) {
        free(sb);
        return r;
    }
    if (sb->hello.state != VB_STATE_CONFIGURED) {
        fprintf(stderr, "hm2pinout: virtual %s at %s is blank (no firmware loaded)\n",
                sb->hello.board, path);
        hm2_sim_teardown(sb);
        free(sb);
        return -ENODEV;
    }
    sb->llio.reset = NULL;
    sb->llio.program_fpga = NULL;
    *llio = &sb->llio;
    *handle = sb;
    return 0;
}

void hm2pinout_close_sim(void *handle)
{
    struct hm2_sim_board *sb = handle;
    if (!sb)
        return;
    hm2_sim_teardown(sb);
    free(sb);
}
