/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The board drivers' realtime-module skeleton (see hm2_board_module.h). */
#include <errno.h>
#include <stdlib.h>

#include "hal.h"
#include "hm2/hm2.h"
#include "hm2_board_module.h"
#include "rtapi.h"

static void release_all(struct hm2_board_module *m, const struct hm2_board_module_desc *d)
{
    if (!m->slots)
        return;
    for (int i = 0; i < d->max_boards; i++)
        d->release(m->slots, i);
    free(m->slots);
    m->slots = NULL;
}

int hm2_board_module_load(struct hm2_board_module *m, const struct hm2_board_module_desc *d)
{
    int r = 0, n = 0;
    m->slots = NULL;
    m->comp_id = hal_init(d->name);
    if (m->comp_id < 0)
        return m->comp_id;
    m->slots = calloc((size_t)d->max_boards, d->slot_size);
    if (!m->slots) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: out of memory for %d board slots\n", d->name,
                        d->max_boards);
        r = -ENOMEM;
        goto fail;
    }
    for (int i = 0; i < d->max_boards && d->wanted(i); i++) {
        r = d->setup(m->slots, i, m->comp_id);
        if (r)
            goto fail;
        n++;
    }
    if (n == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: %s\n", d->name, d->none_given);
        r = -EINVAL;
        goto fail;
    }
    hal_ready(m->comp_id);
    return 0;
fail:
    release_all(m, d);
    hal_exit(m->comp_id);
    m->comp_id = -1;
    return r;
}

void hm2_board_module_unload(struct hm2_board_module *m, const struct hm2_board_module_desc *d)
{
    release_all(m, d);
    if (m->comp_id >= 0)
        hal_exit(m->comp_id);
    m->comp_id = -1;
    rtapi_print("%s: driver unloaded\n", d->name);
}

void hm2_board_rtapi_log(void *ctx, int level, const char *line)
{
    (void)ctx;
    switch (level) {
    case HM2_PRINT: rtapi_print("%s\n", line); break;
    case HM2_ERR: rtapi_print_msg(RTAPI_MSG_ERR, "%s\n", line); break;
    case HM2_WARN: rtapi_print_msg(RTAPI_MSG_WARN, "%s\n", line); break;
    case HM2_INFO: rtapi_print_msg(RTAPI_MSG_INFO, "%s\n", line); break;
    default: rtapi_print_msg(RTAPI_MSG_DBG, "%s\n", line); break;
    }
}
