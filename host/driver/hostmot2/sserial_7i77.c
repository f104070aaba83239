/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * sserial_7i77.c - the 7I77 behind two Smart Serial channels (sserial(9)):
 * its field I/O channel has the 7I76's pins and process data
 * (sserial_7i76.c), its analog servo channel (hm2_<b>.7i77.P.C+1) has
 *   analogout0..5 (float in), analogena (bit in) and per output the params
 *   analogoutN-scalemax (default 10), -minlim (-10), -maxlim (10).
 * Analog process data (docs/sserial.md): host -> 7I77, 91 bits: outputs
 * 0..5 as 15-bit two's complement at 0, 15, ..., 75 (+-16383 = +-scalemax),
 * analog enable at 90.  The remote's sizes tell the two channels apart.
 */
#include <errno.h>
#include <math.h>

#include "sserial.h"

#define N_AOUT 6
#define AOUT_BITS 15
#define AOUT_FULL 16383.0
#define IO_OUT_BITS 48
#define ANALOG_OUT_BITS (N_AOUT * AOUT_BITS + 1)

struct ss_7i77a_hal {
    hal_float_t *out[N_AOUT];
    hal_bit_t *ena;
    hal_float_t scalemax[N_AOUT], minlim[N_AOUT], maxlim[N_AOUT];
};

static int analog_setup(hostmot2_t *hm2, struct ss_chan *ch, const char *pfx)
{
    struct ss_7i77a_hal *h = hm2_hal_zalloc(hm2, sizeof(*h), "7i77 analog pins");
    if (!h)
        return -ENOMEM;
    int id = hm2->llio->comp_id, r = 0;
    for (int i = 0; i < N_AOUT && !r; i++) {
        r = hal_pin_float_newf(HAL_IN, &h->out[i], id, "%s.analogout%d", pfx, i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &h->scalemax[i], id, "%s.analogout%d-scalemax",
                                     pfx, i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &h->minlim[i], id, "%s.analogout%d-minlim", pfx, i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &h->maxlim[i], id, "%s.analogout%d-maxlim", pfx, i);
    }
    if (!r)
        r = hal_pin_bit_newf(HAL_IN, &h->ena, id, "%s.analogena", pfx);
    if (r)
        return hm2_hal_fail(hm2, r, "7i77 analog");
    for (int i = 0; i < N_AOUT; i++) {
        *h->out[i] = 0.0;
        h->scalemax[i] = 10.0;
        h->minlim[i] = -10.0;
        h->maxlim[i] = 10.0;
    }
    *h->ena = 0;
    ch->hal = h;
    return 0;
}

static int r7i77_setup(hostmot2_t *hm2, struct ss_chan *ch, const char *pfx)
{
    if (ch->out_bits == IO_OUT_BITS)
        return hm2_ss_7i76.setup(hm2, ch, pfx);
    if (ch->out_bits == ANALOG_OUT_BITS && ch->in_bits == 0)
        return analog_setup(hm2, ch, pfx);
    hm2_msg(hm2, HM2_ERR,
            "Smart Serial port %d channel %d: 7i77 with %d bits in, %d out is neither its field "
            "I/O (%d out) nor its analog channel (0 in, %d out)",
            ch->port, ch->chan, ch->in_bits, ch->out_bits, IO_OUT_BITS, ANALOG_OUT_BITS);
    return -EINVAL;
}

/* value -> 15-bit two's complement: clamp to [minlim, maxlim], scale so
 * that +-scalemax is full scale. */
static uint32_t dac(const struct ss_7i77a_hal *h, int i)
{
    double v = *h->out[i];
    if (v > h->maxlim[i])
        v = h->maxlim[i];
    if (v < h->minlim[i])
        v = h->minlim[i];
    if (!(fabs(h->scalemax[i]) > 0.0) || !isfinite(v))
        return 0;
    double f = v / h->scalemax[i];
    f = f > 1.0 ? 1.0 : f < -1.0 ? -1.0 : f;
    long c = lround(f * AOUT_FULL);
    return (uint32_t)c & ((1u << AOUT_BITS) - 1u);
}

static void put(uint32_t out[3], int pos, int width, uint32_t v)
{
    for (int k = 0; k < width; k++, pos++)
        if ((v >> k) & 1u)
            out[pos / 32] |= 1u << (pos % 32);
}

static void r7i77_pack(struct ss_chan *ch, uint32_t out[3])
{
    if (ch->out_bits == IO_OUT_BITS) {
        hm2_ss_7i76.pack(ch, out);
        return;
    }
    const struct ss_7i77a_hal *h = ch->hal;
    out[0] = out[1] = out[2] = 0;
    for (int i = 0; i < N_AOUT; i++)
        put(out, i * AOUT_BITS, AOUT_BITS, dac(h, i));
    put(out, N_AOUT * AOUT_BITS, 1, *h->ena ? 1u : 0u);
}

static void r7i77_unpack(struct ss_chan *ch, const uint32_t in[3])
{
    if (ch->out_bits == IO_OUT_BITS)
        hm2_ss_7i76.unpack(ch, in);
}

const struct ss_remote_type hm2_ss_7i77 = {
    .name = "7i77",
    .setup = r7i77_setup,
    .pack = r7i77_pack,
    .unpack = r7i77_unpack,
};
