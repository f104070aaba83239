/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Raw register access pins (config `enable_raw`, spec §13): peek at
 * read_address every read(), poke write_data to write_address when
 * write_strobe is set; dump_state prints the board state once. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "module_api.h"

struct raw_hal {
    hal_u32_t *read_address, *read_data, *write_address, *write_data;
    hal_bit_t *write_strobe, *dump_state;
};

struct hm2_raw_state {
    struct raw_hal *hal;
};

static int raw_setup(hostmot2_t *hm2)
{
    if (!hm2->config.enable_raw)
        return 0;
    struct hm2_raw_state *s = calloc(1, sizeof(*s));
    if (!s) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating raw state");
        return -ENOMEM;
    }
    hm2->raw_s = s;
    s->hal = hm2_hal_zalloc(hm2, sizeof(*s->hal), "raw pins");
    if (!s->hal)
        return -ENOMEM;
    struct raw_hal *h = s->hal;
    const char *pfx = hm2->llio->name;
    int id = hm2->llio->comp_id, r;
    if ((r = hal_pin_u32_newf(HAL_IN, &h->read_address, id, "%s.raw.read_address", pfx)) ||
        (r = hal_pin_u32_newf(HAL_OUT, &h->read_data, id, "%s.raw.read_data", pfx)) ||
        (r = hal_pin_u32_newf(HAL_IN, &h->write_address, id, "%s.raw.write_address", pfx)) ||
        (r = hal_pin_u32_newf(HAL_IN, &h->write_data, id, "%s.raw.write_data", pfx)) ||
        (r = hal_pin_bit_newf(HAL_IN, &h->write_strobe, id, "%s.raw.write_strobe", pfx)) ||
        (r = hal_pin_bit_newf(HAL_IO, &h->dump_state, id, "%s.raw.dump_state", pfx)))
        return hm2_hal_fail(hm2, r, "raw");
    *h->read_address = *h->read_data = *h->write_address = *h->write_data = 0;
    *h->write_strobe = *h->dump_state = 0;
    return 0;
}

static void raw_process_read(hostmot2_t *hm2, long period)
{
    (void)period;
    struct hm2_raw_state *s = hm2->raw_s;
    if (!s)
        return;
    uint32_t addr = *s->hal->read_address & 0xFFFCu;
    uint32_t v = 0;
    if (hm2_read_reg(hm2, addr, &v) == 0)
        *s->hal->read_data = v;
    if (*s->hal->dump_state) {
        hm2_print_idrom(hm2);
        hm2_print_modules(hm2);
        hm2_print_pin_usage(hm2);
        *s->hal->dump_state = 0;
    }
}

static void raw_write_changed(hostmot2_t *hm2)
{
    struct hm2_raw_state *s = hm2->raw_s;
    if (!s || !*s->hal->write_strobe)
        return;
    hm2_write_cfg(hm2, *s->hal->write_address & 0xFFFCu, *s->hal->write_data);
}

static void raw_cleanup(hostmot2_t *hm2)
{
    free(hm2->raw_s);
    hm2->raw_s = NULL;
}

const struct hm2_module_ops hm2_raw_ops = {
    .name = "raw",
    .setup = raw_setup,
    .process_read = raw_process_read,
    .write_changed = raw_write_changed,
    .cleanup = raw_cleanup,
};
