/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * sserial_7i76.c - the 7I76 behind a Smart Serial channel: its HAL pins
 * and params (sserial(9): input-NN, output-NN, spinout, spinena, spindir,
 * analogin0..3, fieldvoltage) and its process data (docs/sserial.md):
 *   host -> 7I76: bits 0..15 outputs, 16 spindle enable, 17 spindle
 *       direction, 32..47 spindle DAC (0..65535 = 0..full scale)
 *   7I76 -> host: 0..31 inputs; modes 1, 2: analog inputs 0..3, 12 bits
 *       each at 32, 44, 56, 68 (LSB 0.01 V); mode 2: field voltage at 80.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>

#include "sserial.h"

#define N_IN 32
#define N_OUT 16
#define N_ANALOG 4
#define ADC_LSB_V 0.01

struct ss_7i76_hal {
    hal_bit_t *input[N_IN], *input_not[N_IN];
    hal_bit_t *output[N_OUT];
    hal_float_t *spinout;
    hal_bit_t *spinena, *spindir;
    hal_float_t *analogin[N_ANALOG], *fieldvoltage;
    /* params */
    hal_bit_t output_invert[N_OUT];
    hal_bit_t spinena_invert, spindir_invert;
    hal_float_t spinout_scalemax, spinout_minlim, spinout_maxlim;
    hal_u32_t nvunitnumber;
};

static int export_pins(struct ss_7i76_hal *h, int id, const char *pfx, int mode)
{
    int r = 0;
    for (int i = 0; i < N_IN && !r; i++) {
        r = hal_pin_bit_newf(HAL_OUT, &h->input[i], id, "%s.input-%02d", pfx, i);
        if (!r)
            r = hal_pin_bit_newf(HAL_OUT, &h->input_not[i], id, "%s.input-%02d-not", pfx, i);
    }
    for (int i = 0; i < N_OUT && !r; i++) {
        r = hal_pin_bit_newf(HAL_IN, &h->output[i], id, "%s.output-%02d", pfx, i);
        if (!r)
            r = hal_param_bit_newf(HAL_RW, &h->output_invert[i], id, "%s.output-%02d-invert",
                                   pfx, i);
    }
    if (!r)
        r = hal_pin_float_newf(HAL_IN, &h->spinout, id, "%s.spinout", pfx);
    if (!r)
        r = hal_pin_bit_newf(HAL_IN, &h->spinena, id, "%s.spinena", pfx);
    if (!r)
        r = hal_pin_bit_newf(HAL_IN, &h->spindir, id, "%s.spindir", pfx);
    for (int i = 0; i < N_ANALOG && mode >= 1 && !r; i++)
        r = hal_pin_float_newf(HAL_OUT, &h->analogin[i], id, "%s.analogin%d", pfx, i);
    if (!r && mode == 2)
        r = hal_pin_float_newf(HAL_OUT, &h->fieldvoltage, id, "%s.fieldvoltage", pfx);
    return r;
}

static int export_params(struct ss_7i76_hal *h, int id, const char *pfx)
{
    int r = hal_param_bit_newf(HAL_RW, &h->spinena_invert, id, "%s.spinena-invert", pfx);
    if (!r)
        r = hal_param_bit_newf(HAL_RW, &h->spindir_invert, id, "%s.spindir-invert", pfx);
    if (!r)
        r = hal_param_float_newf(HAL_RW, &h->spinout_scalemax, id, "%s.spinout-scalemax", pfx);
    if (!r)
        r = hal_param_float_newf(HAL_RW, &h->spinout_minlim, id, "%s.spinout-minlim", pfx);
    if (!r)
        r = hal_param_float_newf(HAL_RW, &h->spinout_maxlim, id, "%s.spinout-maxlim", pfx);
    if (!r)
        r = hal_param_u32_newf(HAL_RO, &h->nvunitnumber, id, "%s.nvunitnumber", pfx);
    return r;
}

static int r7i76_setup(hostmot2_t *hm2, struct ss_chan *ch, const char *pfx)
{
    struct ss_7i76_hal *h = hm2_hal_zalloc(hm2, sizeof(*h), "7i76 pins");
    if (!h)
        return -ENOMEM;
    int id = hm2->llio->comp_id;
    int r = export_pins(h, id, pfx, ch->mode);
    if (!r)
        r = export_params(h, id, pfx);
    if (r)
        return hm2_hal_fail(hm2, r, "7i76");
    for (int i = 0; i < N_IN; i++) {
        *h->input[i] = 0;
        *h->input_not[i] = 1;
    }
    for (int i = 0; i < N_OUT; i++)
        *h->output[i] = 0;
    *h->spinout = 0;
    *h->spinena = *h->spindir = 0;
    h->spinout_scalemax = 100.0;
    h->spinout_minlim = 0.0;
    h->spinout_maxlim = 100.0;
    h->nvunitnumber = ch->unit;
    ch->hal = h;
    return 0;
}

/* spinout (in speed units) -> DAC counts: clamped to [minlim, maxlim],
 * scaled so that scalemax is full scale; the DAC is unipolar (direction
 * is spindir), so the magnitude is used. */
static uint32_t dac_counts(const struct ss_7i76_hal *h)
{
    double v = *h->spinout;
    if (v > h->spinout_maxlim)
        v = h->spinout_maxlim;
    if (v < h->spinout_minlim)
        v = h->spinout_minlim;
    double scale = h->spinout_scalemax;
    if (!(fabs(scale) > 0.0) || !isfinite(v))
        return 0;
    double f = fabs(v / scale);
    if (f > 1.0)
        f = 1.0;
    return (uint32_t)lround(f * 65535.0);
}

static void r7i76_pack(struct ss_chan *ch, uint32_t out[3])
{
    const struct ss_7i76_hal *h = ch->hal;
    uint32_t w = 0;
    for (int i = 0; i < N_OUT; i++)
        if ((*h->output[i] != 0) != (h->output_invert[i] != 0))
            w |= 1u << i;
    if ((*h->spinena != 0) != (h->spinena_invert != 0))
        w |= 1u << 16;
    if ((*h->spindir != 0) != (h->spindir_invert != 0))
        w |= 1u << 17;
    out[0] = w;
    out[1] = dac_counts(h);
    out[2] = 0;
}

static uint32_t field(const uint32_t in[3], int pos, int width)
{
    uint64_t lo = in[pos / 32], hi = pos / 32 + 1 < 3 ? in[pos / 32 + 1] : 0;
    uint64_t v = (lo | hi << 32) >> (pos % 32);
    return (uint32_t)(v & ((1u << width) - 1u));
}

static void r7i76_unpack(struct ss_chan *ch, const uint32_t in[3])
{
    struct ss_7i76_hal *h = ch->hal;
    for (int i = 0; i < N_IN; i++) {
        hal_bit_t b = (in[0] >> i) & 1u;
        *h->input[i] = b;
        *h->input_not[i] = !b;
    }
    if (ch->mode >= 1)
        for (int i = 0; i < N_ANALOG; i++)
            *h->analogin[i] = field(in, 32 + 12 * i, 12) * ADC_LSB_V;
    if (ch->mode == 2)
        *h->fieldvoltage = field(in, 80, 12) * ADC_LSB_V;
}

const struct ss_remote_type hm2_ss_7i76 = {
    .name = "7i76",
    .setup = r7i76_setup,
    .pack = r7i76_pack,
    .unpack = r7i76_unpack,
};
