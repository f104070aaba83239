/* SPDX-License-Identifier: GPL-2.0-or-later */
/* IOPort / GPIO (spec §9.1, §10.5): HAL pins for every I/O pin, the data
 * registers in the TRAM, direction/open-drain/invert/source registers
 * written when they change (and in glitch-free order at force-write). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modules.h"

struct hm2_gpio_hal {
    hal_bit_t *in, *in_not, *out;
    hal_bit_t is_output, is_opendrain, invert_output;
};

enum { REG_DATA = 0, REG_DDR = 1, REG_ALT = 2, REG_OD = 3, REG_INV = 4 };

struct hm2_ioport_state {
    int num_ports, width;
    uint32_t *data_read;  /* TRAM */
    uint32_t *data_write; /* TRAM */
    uint32_t cfg[5][HM2_LLIO_MAX_CONNECTORS];   /* wanted (index REG_*) */
    uint32_t wrote[5][HM2_LLIO_MAX_CONNECTORS]; /* last written */
    bool module_outputs;                        /* DDR of module outputs on */
    int early_gtag; /* this module's outputs are on before that (0: none) */
    struct hm2_gpio_hal *hal;
};

static int export_pin(hostmot2_t *hm2, int i, struct hm2_gpio_hal *h)
{
    const char *pfx = hm2->llio->name;
    int id = hm2->llio->comp_id;
    struct hm2_pin *p = &hm2->pin[i];
    char what[80];
    int r;

    snprintf(what, sizeof(what), "gpio.%03d", i);
    if ((r = hal_pin_bit_newf(HAL_OUT, &h->in, id, "%s.gpio.%03d.in", pfx, i)) ||
        (r = hal_pin_bit_newf(HAL_OUT, &h->in_not, id, "%s.gpio.%03d.in_not", pfx, i)))
        return hm2_hal_fail(hm2, r, what);
    bool full = p->gtag == HM2_GTAG_IOPORT;
    if (full) {
        if ((r = hal_pin_bit_newf(HAL_IN, &h->out, id, "%s.gpio.%03d.out", pfx, i)) ||
            (r = hal_param_bit_newf(HAL_RW, &h->is_output, id, "%s.gpio.%03d.is_output", pfx, i)))
            return hm2_hal_fail(hm2, r, what);
        *h->out = 0;
    }
    if (full || p->direction == HM2_PIN_DIR_OUTPUT) {
        if ((r = hal_param_bit_newf(HAL_RW, &h->is_opendrain, id, "%s.gpio.%03d.is_opendrain", pfx,
                                    i)) ||
            (r = hal_param_bit_newf(HAL_RW, &h->invert_output, id, "%s.gpio.%03d.invert_output",
                                    pfx, i)))
            return hm2_hal_fail(hm2, r, what);
    }
    h->is_output = 0;
    h->is_opendrain = 0;
    h->invert_output = 0;
    *h->in = 0;
    *h->in_not = 1;
    return 0;
}

/* Module output pins get aliases named after their function:
 * <pfx>.<mod>.<UU>.<stem>.invert_output, or .<UU>.<k>.<stem>. when several
 * pins share unit and signal. */
static int alias_pin(hostmot2_t *hm2, int i)
{
    const struct hm2_pin *p = &hm2->pin[i];
    const char *mod = hm2_get_hal_module_name(p->gtag);
    const char *stem = hm2_get_pin_secondary_hal_name(p);
    if (!mod || !stem || p->direction != HM2_PIN_DIR_OUTPUT)
        return 0;
    int same = 0, k = 0;
    for (int j = 0; j < hm2->num_pins; j++) {
        const struct hm2_pin *q = &hm2->pin[j];
        if (q->gtag == p->gtag && q->sec_unit == p->sec_unit &&
            (q->sec_pin & 0x7F) == (p->sec_pin & 0x7F)) {
            if (j < i)
                k++;
            same++;
        }
    }
    static const char *const params[2] = {"invert_output", "is_opendrain"};
    for (int n = 0; n < 2; n++) {
        char name[128], alias[128];
        snprintf(name, sizeof(name), "%s.gpio.%03d.%s", hm2->llio->name, i, params[n]);
        int unit = p->sec_unit & 0x7F;
        if (same > 1)
            snprintf(alias, sizeof(alias), "%s.%s.%02d.%d.%s.%s", hm2->llio->name, mod, unit, k,
                     stem, params[n]);
        else
            snprintf(alias, sizeof(alias), "%s.%s.%02d.%s.%s", hm2->llio->name, mod, unit, stem,
                     params[n]);
        int r = hal_param_alias(name, alias);
        if (r)
            return hm2_hal_fail(hm2, r, alias);
    }
    return 0;
}

static int ioport_setup(hostmot2_t *hm2)
{
    if (!hm2->ioport.present || hm2->num_pins == 0)
        return 0;
    struct hm2_ioport_state *s = calloc(1, sizeof(*s));
    if (!s) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating IOPort state");
        return -ENOMEM;
    }
    hm2->ioport_s = s;
    s->num_ports = (int)hm2->idrom.io_ports;
    s->width = (int)hm2->idrom.port_width;
    int r;
    if ((r = hm2_tram_add_read(hm2, hm2_reg_addr(&hm2->ioport.md, REG_DATA, 0), &s->data_read,
                               s->num_ports)) ||
        (r = hm2_tram_add_write(hm2, hm2_reg_addr(&hm2->ioport.md, REG_DATA, 0), &s->data_write,
                                s->num_ports)))
        return r;
    /* instance stride is 4 (checked at MD acceptance): one block per register */
    s->hal = hm2_hal_zalloc(hm2, sizeof(*s->hal) * (size_t)hm2->num_pins, "GPIO pins");
    if (!s->hal)
        return -ENOMEM;
    for (int i = 0; i < hm2->num_pins; i++) {
        hm2->pin[i].hal = &s->hal[i];
        if ((r = export_pin(hm2, i, &s->hal[i])) || (r = alias_pin(hm2, i)))
            return r;
    }
    return 0;
}

static void compute_config(hostmot2_t *hm2)
{
    struct hm2_ioport_state *s = hm2->ioport_s;
    memset(s->cfg[REG_DDR], 0, sizeof(s->cfg[0]) * 4);
    for (int i = 0; i < hm2->num_pins; i++) {
        const struct hm2_pin *p = &hm2->pin[i];
        const struct hm2_gpio_hal *h = p->hal;
        uint32_t bit = 1u << p->port_pin;
        int port = p->port_num;
        bool output;
        if (p->gtag == HM2_GTAG_IOPORT) {
            output = h->is_output;
        } else {
            s->cfg[REG_ALT][port] |= bit;
            output = p->direction == HM2_PIN_DIR_OUTPUT;
            if (output && !s->module_outputs && p->gtag != s->early_gtag)
                continue;
        }
        if (!output)
            continue;
        s->cfg[REG_DDR][port] |= bit;
        if (h->is_opendrain)
            s->cfg[REG_OD][port] |= bit;
        if (h->invert_output)
            s->cfg[REG_INV][port] |= bit;
    }
}

static void write_config(hostmot2_t *hm2, bool force)
{
    struct hm2_ioport_state *s = hm2->ioport_s;
    /* invert and open drain before source and direction: no glitches */
    static const int order[4] = {REG_INV, REG_OD, REG_ALT, REG_DDR};
    compute_config(hm2);
    for (int k = 0; k < 4; k++) {
        int reg = order[k];
        for (int port = 0; port < s->num_ports; port++) {
            if (!force && s->cfg[reg][port] == s->wrote[reg][port])
                continue;
            if (hm2_write_cfg(hm2, hm2_reg_addr(&hm2->ioport.md, reg, port), s->cfg[reg][port]) == 0)
                s->wrote[reg][port] = s->cfg[reg][port];
        }
    }
}

int hm2_ioport_early_outputs(hostmot2_t *hm2, int gtag)
{
    struct hm2_ioport_state *s = hm2->ioport_s;
    if (!s)
        return -ENODEV;
    s->early_gtag = gtag;
    write_config(hm2, false);
    return hm2->needs_reset ? -EIO : 0;
}

static void ioport_force_write(hostmot2_t *hm2)
{
    if (hm2->ioport_s)
        write_config(hm2, true);
}

static void ioport_write_changed(hostmot2_t *hm2)
{
    if (hm2->ioport_s)
        write_config(hm2, false);
}

static void gpio_inputs(hostmot2_t *hm2)
{
    struct hm2_ioport_state *s = hm2->ioport_s;
    if (!s)
        return;
    for (int i = 0; i < hm2->num_pins; i++) {
        const struct hm2_pin *p = &hm2->pin[i];
        bool v = (s->data_read[p->port_num] >> p->port_pin) & 1u;
        *p->hal->in = v;
        *p->hal->in_not = !v;
    }
}

static void gpio_outputs(hostmot2_t *hm2)
{
    struct hm2_ioport_state *s = hm2->ioport_s;
    if (!s)
        return;
    memset(s->data_write, 0, sizeof(uint32_t) * (size_t)s->num_ports);
    for (int i = 0; i < hm2->num_pins; i++) {
        const struct hm2_pin *p = &hm2->pin[i];
        if (p->gtag == HM2_GTAG_IOPORT && *p->hal->out)
            s->data_write[p->port_num] |= 1u << p->port_pin;
    }
}

int hm2_ioport_read_gpio(hostmot2_t *hm2)
{
    struct hm2_ioport_state *s = hm2->ioport_s;
    if (!s)
        return 0;
    int r = hm2->llio->read(hm2->llio, hm2_reg_addr(&hm2->ioport.md, REG_DATA, 0), s->data_read,
                            4u * (size_t)s->num_ports);
    if (r)
        return r;
    gpio_inputs(hm2);
    return 0;
}

int hm2_ioport_write_gpio(hostmot2_t *hm2)
{
    struct hm2_ioport_state *s = hm2->ioport_s;
    if (!s)
        return 0;
    write_config(hm2, false);
    gpio_outputs(hm2);
    return hm2->llio->write(hm2->llio, hm2_reg_addr(&hm2->ioport.md, REG_DATA, 0), s->data_write,
                            4u * (size_t)s->num_ports);
}

static void ioport_process_read(hostmot2_t *hm2, long period)
{
    (void)period;
    gpio_inputs(hm2);
}

static void ioport_prepare_write(hostmot2_t *hm2, long period)
{
    /* module outputs get their DDR bits from the first HAL write() on, not
     * at load (LinuxCNC 2.9: no output drives before the threads run) */
    if (hm2->ioport_s && period != HM2_LOAD_PERIOD)
        hm2->ioport_s->module_outputs = true;
    gpio_outputs(hm2);
}

static void ioport_cleanup(hostmot2_t *hm2)
{
    free(hm2->ioport_s);
    hm2->ioport_s = NULL;
}

const struct hm2_module_ops hm2_ioport_ops = {
    .name = "ioport",
    .setup = ioport_setup,
    .process_read = ioport_process_read,
    .prepare_write = ioport_prepare_write,
    .write_changed = ioport_write_changed,
    .force_write = ioport_force_write,
    .cleanup = ioport_cleanup,
};
