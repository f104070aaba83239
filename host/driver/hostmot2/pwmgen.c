/* SPDX-License-Identifier: GPL-2.0-or-later */
/* PWMGen (spec §9.6, §10.3): value registers every period; mode, enable
 * and the PWM/PDM DDS rates rewritten together when any of them changes. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>

#include "module_api.h"

enum { REG_VALUE = 0, REG_MODE = 1, REG_PWMRATE = 2, REG_PDMRATE = 3, REG_ENABLE = 4 };

struct pwm_hal {
    hal_float_t *value;
    hal_bit_t *enable;
    hal_float_t scale;
    hal_s32_t output_type;
    hal_bit_t offset_mode, dither;
};

struct pwm_global_hal {
    hal_u32_t pwm_frequency, pdm_frequency;
};

struct pwm_written {
    int32_t output_type;
    bool offset_mode, dither, enable;
};

struct hm2_pwmgen_state {
    const struct hm2_md *md;
    int num;
    bool dither_capable, has_enable_reg;
    struct pwm_hal *hal;
    struct pwm_global_hal *ghal;
    uint32_t *value; /* TRAM write */
    int pwm_bits;
    bool config_written;
    uint32_t w_pwm_frequency, w_pdm_frequency;
    struct pwm_written *w;
};

static int pwmgen_setup(hostmot2_t *hm2)
{
    if (!hm2->pwmgen.present || hm2->pwmgen.used == 0)
        return 0;
    struct hm2_pwmgen_state *s = calloc(1, sizeof(*s));
    if (!s) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating pwmgen state");
        return -ENOMEM;
    }
    hm2->pwmgen_s = s;
    s->md = &hm2->pwmgen.md;
    s->num = hm2->pwmgen.used;
    s->dither_capable = s->md->version == 1;
    for (int i = 0; i < hm2->num_pins; i++)
        if (hm2->pin[i].sec_tag == HM2_GTAG_PWMGEN && (hm2->pin[i].sec_pin & 0x7F) == 3)
            s->has_enable_reg = true;
    s->w = calloc((size_t)s->num, sizeof(*s->w));
    s->hal = hm2_hal_zalloc(hm2, sizeof(*s->hal) * (size_t)s->num, "pwmgen pins");
    s->ghal = hm2_hal_zalloc(hm2, sizeof(*s->ghal), "pwmgen parameters");
    if (!s->w || !s->hal || !s->ghal) {
        if (!s->w)
            hm2_msg(hm2, HM2_ERR, "out of memory allocating pwmgen state");
        return -ENOMEM;
    }
    const char *pfx = hm2->llio->name;
    int id = hm2->llio->comp_id, r;
    if ((r = hal_param_u32_newf(HAL_RW, &s->ghal->pwm_frequency, id, "%s.pwmgen.pwm_frequency",
                                pfx)) ||
        (r = hal_param_u32_newf(HAL_RW, &s->ghal->pdm_frequency, id, "%s.pwmgen.pdm_frequency",
                                pfx)))
        return hm2_hal_fail(hm2, r, "pwmgen");
    s->ghal->pwm_frequency = 20000;
    s->ghal->pdm_frequency = 20000;
    for (int i = 0; i < s->num && !r; i++) {
        struct pwm_hal *h = &s->hal[i];
        r = hal_pin_float_newf(HAL_IN, &h->value, id, "%s.pwmgen.%02d.value", pfx, i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &h->enable, id, "%s.pwmgen.%02d.enable", pfx, i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &h->scale, id, "%s.pwmgen.%02d.scale", pfx, i);
        if (!r)
            r = hal_param_s32_newf(HAL_RW, &h->output_type, id, "%s.pwmgen.%02d.output-type", pfx,
                                   i);
        if (!r)
            r = hal_param_bit_newf(HAL_RW, &h->offset_mode, id, "%s.pwmgen.%02d.offset-mode", pfx,
                                   i);
        if (!r && s->dither_capable)
            r = hal_param_bit_newf(HAL_RW, &h->dither, id, "%s.pwmgen.%02d.dither", pfx, i);
        if (r) {
            char what[32];
            snprintf(what, sizeof(what), "pwmgen.%02d", i);
            return hm2_hal_fail(hm2, r, what);
        }
        *h->value = 0.0;
        *h->enable = 0;
        h->scale = 1.0;
        h->output_type = 1;
        h->offset_mode = 0;
        h->dither = 0;
    }
    return hm2_tram_add_write(hm2, hm2_reg_addr(s->md, REG_VALUE, 0), &s->value, s->num);
}

static void pwmgen_force_write(hostmot2_t *hm2);

static void pwmgen_prepare_write(hostmot2_t *hm2, long period)
{
    (void)period;
    struct hm2_pwmgen_state *s = hm2->pwmgen_s;
    if (!s)
        return;
    if (!s->config_written)
        pwmgen_force_write(hm2); /* pwm_bits is known only after a config write */
    for (int i = 0; i < s->num; i++) {
        struct pwm_hal *h = &s->hal[i];
        if (h->scale == 0.0) {
            /* value/scale is meaningless: like a zero encoder scale, reset it */
            hm2_msg(hm2, HM2_ERR, "pwmgen.%02d.scale is 0, setting it to 1.0", i);
            h->scale = 1.0;
        }
        int type = (h->output_type >= 1 && h->output_type <= 4) ? h->output_type : 1;
        s->value[i] = hm2_pwmgen_value_register(*h->value, h->scale, *h->enable, type, s->pwm_bits,
                                                h->offset_mode, s->dither_capable && h->dither);
    }
}

static bool config_changed(const struct hm2_pwmgen_state *s)
{
    if (!s->config_written || s->ghal->pwm_frequency != s->w_pwm_frequency ||
        s->ghal->pdm_frequency != s->w_pdm_frequency)
        return true;
    for (int i = 0; i < s->num; i++) {
        const struct pwm_hal *h = &s->hal[i];
        const struct pwm_written *w = &s->w[i];
        if (h->output_type != w->output_type || h->offset_mode != w->offset_mode ||
            h->dither != w->dither || *h->enable != w->enable)
            return true;
    }
    return false;
}

static void write_reg(hostmot2_t *hm2, int reg, int inst, uint32_t v)
{
    hm2_write_cfg(hm2, hm2_reg_addr(hm2->pwmgen_s->md, reg, inst), v);
}

static void pwmgen_force_write(hostmot2_t *hm2)
{
    struct hm2_pwmgen_state *s = hm2->pwmgen_s;
    if (!s)
        return;
    uint32_t clock = s->md->clock_freq;
    if (s->ghal->pwm_frequency < 1) {
        hm2_msg(hm2, HM2_ERR, "pwmgen.pwm_frequency %u Hz is too low, setting it to 1 Hz",
                (unsigned)s->ghal->pwm_frequency);
        s->ghal->pwm_frequency = 1;
    }
    struct hm2_pwm_rate rate = hm2_pwmgen_pwm_rate(s->ghal->pwm_frequency, clock);
    if (rate.clipped) {
        hm2_msg(hm2, HM2_ERR, "pwmgen.pwm_frequency %u Hz is too high: max PWM frequency is %d Hz",
                (unsigned)s->ghal->pwm_frequency, (int)rate.frequency);
        s->ghal->pwm_frequency = rate.frequency;
    }
    s->pwm_bits = rate.bits;
    int clip;
    uint32_t pdm = hm2_pwmgen_pdm_rate(s->ghal->pdm_frequency, clock, &clip);
    if (clip) {
        uint32_t f = (uint32_t)((double)pdm * (double)clock / 65536.0);
        hm2_msg(hm2, HM2_ERR, "pwmgen.pdm_frequency %u Hz is too %s, setting it to the %s: %u Hz",
                (unsigned)s->ghal->pdm_frequency, clip < 0 ? "low" : "high",
                clip < 0 ? "min" : "max", (unsigned)f);
        s->ghal->pdm_frequency = f;
    }
    uint32_t enables = 0;
    for (int i = 0; i < s->num; i++) {
        struct pwm_hal *h = &s->hal[i];
        bool bad;
        uint32_t mode = hm2_pwmgen_mode_word(h->output_type, s->pwm_bits,
                                             s->dither_capable && h->dither, &bad);
        if (bad) {
            hm2_msg(hm2, HM2_ERR,
                    "pwmgen.%02d.output-type %d is invalid (1 PWM/Dir, 2 Up/Down, 3 PDM/Dir, 4 "
                    "Dir/PWM), using 1",
                    i, (int)h->output_type);
            h->output_type = 1;
        }
        write_reg(hm2, REG_MODE, i, mode);
        if (*h->enable)
            enables |= 1u << i;
        s->w[i].output_type = h->output_type;
        s->w[i].offset_mode = h->offset_mode;
        s->w[i].dither = h->dither;
        s->w[i].enable = *h->enable;
    }
    write_reg(hm2, REG_PWMRATE, 0, rate.dds);
    write_reg(hm2, REG_PDMRATE, 0, pdm);
    if (s->has_enable_reg)
        write_reg(hm2, REG_ENABLE, 0, enables);
    s->w_pwm_frequency = s->ghal->pwm_frequency;
    s->w_pdm_frequency = s->ghal->pdm_frequency;
    s->config_written = true;
}

static void pwmgen_write_changed(hostmot2_t *hm2)
{
    struct hm2_pwmgen_state *s = hm2->pwmgen_s;
    if (s && config_changed(s))
        pwmgen_force_write(hm2);
}

static void pwmgen_cleanup(hostmot2_t *hm2)
{
    if (hm2->pwmgen_s)
        free(hm2->pwmgen_s->w);
    free(hm2->pwmgen_s);
    hm2->pwmgen_s = NULL;
}

const struct hm2_module_ops hm2_pwmgen_ops = {
    .name = "pwmgen",
    .setup = pwmgen_setup,
    .prepare_write = pwmgen_prepare_write,
    .write_changed = pwmgen_write_changed,
    .force_write = pwmgen_force_write,
    .cleanup = pwmgen_cleanup,
};
