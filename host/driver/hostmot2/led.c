/* SPDX-License-Identifier: GPL-2.0-or-later */
/* LEDs (spec §9.3): pin CR01 is bit 31, CR02 bit 30, ...; written when
 * any pin changes. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "module_api.h"

struct hm2_led_state {
    int num;
    hal_bit_t **pins; /* hal_malloc'd array of pin pointers */
    uint32_t written;
    bool done;
};

static int led_setup(hostmot2_t *hm2)
{
    if (!hm2->led.present || hm2->led.used == 0 || hm2->num_leds <= 0)
        return 0;
    struct hm2_led_state *s = calloc(1, sizeof(*s));
    if (!s) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating LED state");
        return -ENOMEM;
    }
    hm2->led_s = s;
    s->num = hm2->num_leds;
    s->pins = hm2_hal_zalloc(hm2, sizeof(hal_bit_t *) * (size_t)s->num, "LED pins");
    if (!s->pins)
        return -ENOMEM;
    for (int i = 0; i < s->num; i++) {
        int r = hal_pin_bit_newf(HAL_IN, &s->pins[i], hm2->llio->comp_id, "%s.led.CR%02d",
                                 hm2->llio->name, i + 1);
        if (r)
            return hm2_hal_fail(hm2, r, "led");
        *s->pins[i] = 0;
    }
    return 0;
}

static void led_write(hostmot2_t *hm2, bool force)
{
    struct hm2_led_state *s = hm2->led_s;
    if (!s)
        return;
    uint32_t v = 0;
    for (int i = 0; i < s->num; i++)
        if (*s->pins[i])
            v |= 1u << (31 - i);
    if (!force && s->done && v == s->written)
        return;
    if (hm2_write_cfg(hm2, hm2_reg_addr(&hm2->led.md, 0, 0), v))
        return;
    s->written = v;
    s->done = true;
}

static void led_write_changed(hostmot2_t *hm2)
{
    led_write(hm2, false);
}

static void led_force_write(hostmot2_t *hm2)
{
    led_write(hm2, true);
}

static void led_cleanup(hostmot2_t *hm2)
{
    free(hm2->led_s);
    hm2->led_s = NULL;
}

const struct hm2_module_ops hm2_led_ops = {
    .name = "led",
    .setup = led_setup,
    .write_changed = led_write_changed,
    .force_write = led_force_write,
    .cleanup = led_cleanup,
};
