/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Encoder (QCounter, spec §9.5, §10.2): count extension, index/probe
 * latching, timestamp velocity estimation (math.c), the control register
 * and the module-wide timestamp divider and input filter rate. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "module_api.h"

enum { REG_COUNT = 0, REG_CCR = 1, REG_TSDIV = 2, REG_TSCOUNT = 3, REG_QFILTER = 4 };

#define CCR_QUAD_ERROR (1u << 15)
#define CCR_LATCH_PROBE (1u << 13)
#define CCR_PROBE_POL (1u << 12)
#define CCR_FILTER (1u << 11)
#define CCR_COUNTER_MODE (1u << 10)
#define CCR_INDEX_MASK (1u << 9)
#define CCR_INDEX_MASK_POL (1u << 8)
#define CCR_JUST_ONCE (1u << 6)
#define CCR_LATCH_INDEX (1u << 4)
#define CCR_INDEX_POL (1u << 3)

struct enc_hal {
    hal_s32_t *rawcounts, *rawlatch, *count, *count_latched;
    hal_float_t *position, *position_latched, *velocity, *velocity_rpm;
    hal_bit_t *reset, *index_enable, *probe_enable, *probe_invert;
    hal_bit_t *quad_error, *quad_error_enable, *input_a, *input_b, *input_index;
    hal_float_t scale, vel_timeout;
    hal_bit_t index_invert, index_mask, index_mask_invert, counter_mode, filter;
};

struct enc_global_hal {
    hal_u32_t *sample_frequency;
    hal_bit_t *hires_timestamp;
};

struct enc_instance {
    struct enc_hal *hal;
    struct hm2_encoder_track track;
    bool primed;
    uint32_t written_control;
    bool control_written;
    bool prev_qe_enable;
    bool qe_armed; /* the clear for the current quad-error-enable was written */
};

struct hm2_encoder_state {
    const struct hm2_md *md;
    int num;
    bool probe_capable;
    struct enc_instance *inst;
    struct enc_global_hal *ghal;
    uint32_t *tscount, *count, *ccr; /* TRAM */
    uint32_t tsdiv, written_tsdiv;
    uint32_t written_sample_frequency;
    bool written_hires;
};

static int export_instance(hostmot2_t *hm2, int i, struct enc_hal *h, bool probe)
{
    const char *pfx = hm2->llio->name;
    int id = hm2->llio->comp_id, r = 0;
    char what[48];
    snprintf(what, sizeof(what), "encoder.%02d", i);
#define PIN(kind, dir, field, nm) \
    if (!r) r = hal_pin_##kind##_newf(dir, &h->field, id, "%s.encoder.%02d." nm, pfx, i)
#define PAR(kind, field, nm) \
    if (!r) r = hal_param_##kind##_newf(HAL_RW, &h->field, id, "%s.encoder.%02d." nm, pfx, i)
    PIN(s32, HAL_OUT, rawcounts, "rawcounts");
    PIN(s32, HAL_OUT, rawlatch, "rawlatch");
    PIN(s32, HAL_OUT, count, "count");
    PIN(s32, HAL_OUT, count_latched, "count-latched");
    PIN(float, HAL_OUT, position, "position");
    PIN(float, HAL_OUT, position_latched, "position-latched");
    PIN(float, HAL_OUT, velocity, "velocity");
    PIN(float, HAL_OUT, velocity_rpm, "velocity-rpm");
    PIN(bit, HAL_IN, reset, "reset");
    PIN(bit, HAL_IO, index_enable, "index-enable");
    if (probe) {
        PIN(bit, HAL_IN, probe_enable, "probe-enable");
        PIN(bit, HAL_IN, probe_invert, "probe-invert");
    }
    PIN(bit, HAL_OUT, quad_error, "quad-error");
    PIN(bit, HAL_IN, quad_error_enable, "quad-error-enable");
    PIN(bit, HAL_OUT, input_a, "input-a");
    PIN(bit, HAL_OUT, input_b, "input-b");
    PIN(bit, HAL_OUT, input_index, "input-index");
    PAR(float, scale, "scale");
    PAR(bit, index_invert, "index-invert");
    PAR(bit, index_mask, "index-mask");
    PAR(bit, index_mask_invert, "index-mask-invert");
    PAR(bit, counter_mode, "counter-mode");
    PAR(bit, filter, "filter");
    PAR(float, vel_timeout, "vel-timeout");
#undef PIN
#undef PAR
    if (r)
        return hm2_hal_fail(hm2, r, what);
    *h->rawcounts = *h->rawlatch = *h->count = *h->count_latched = 0;
    *h->position = *h->position_latched = *h->velocity = *h->velocity_rpm = 0.0;
    *h->reset = *h->index_enable = *h->quad_error = *h->quad_error_enable = 0;
    *h->input_a = *h->input_b = *h->input_index = 0;
    if (probe)
        *h->probe_enable = *h->probe_invert = 0;
    h->scale = 1.0;
    h->vel_timeout = 0.5;
    h->index_invert = h->index_mask = h->index_mask_invert = h->counter_mode = 0;
    h->filter = 1;
    return 0;
}

static int encoder_setup(hostmot2_t *hm2)
{
    const struct hm2_module *m = hm2->encoder.present ? &hm2->encoder : &hm2->muxed_encoder;
    bool muxed = !hm2->encoder.present;
    if (!m->present || m->used == 0)
        return 0;
    struct hm2_encoder_state *s = calloc(1, sizeof(*s));
    if (!s) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating encoder state");
        return -ENOMEM;
    }
    hm2->encoder_s = s;
    s->md = &m->md;
    s->num = m->used;
    s->probe_capable = m->md.version == 0x83 || m->md.version == 0x84;
    s->inst = calloc((size_t)s->num, sizeof(*s->inst));
    if (!s->inst) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating encoder instances");
        return -ENOMEM;
    }
    struct enc_hal *h = hm2_hal_zalloc(hm2, sizeof(*h) * (size_t)s->num, "encoder pins");
    s->ghal = hm2_hal_zalloc(hm2, sizeof(*s->ghal), "encoder pins");
    if (!h || !s->ghal)
        return -ENOMEM;
    const char *pfx = hm2->llio->name;
    int id = hm2->llio->comp_id, r;
    if ((r = hal_pin_u32_newf(HAL_IN, &s->ghal->sample_frequency, id,
                              muxed ? "%s.encoder.muxed-sample-frequency"
                                    : "%s.encoder.sample-frequency",
                              pfx)) ||
        (r = hal_pin_bit_newf(HAL_IN, &s->ghal->hires_timestamp, id, "%s.encoder.hires-timestamp",
                              pfx)))
        return hm2_hal_fail(hm2, r, "encoder");
    *s->ghal->sample_frequency = muxed ? 8000000u : 25000000u;
    *s->ghal->hires_timestamp = 0;
    for (int i = 0; i < s->num; i++) {
        s->inst[i].hal = &h[i];
        if ((r = export_instance(hm2, i, &h[i], s->probe_capable)))
            return r;
    }
    if ((r = hm2_tram_add_read(hm2, hm2_reg_addr(s->md, REG_TSCOUNT, 0), &s->tscount, 1)) ||
        (r = hm2_tram_add_read(hm2, hm2_reg_addr(s->md, REG_COUNT, 0), &s->count, s->num)) ||
        (r = hm2_tram_add_read(hm2, hm2_reg_addr(s->md, REG_CCR, 0), &s->ccr, s->num)))
        return r;
    return 0;
}

static uint32_t control_word(struct enc_instance *e)
{
    const struct enc_hal *h = e->hal;
    bool index = *h->index_enable;
    bool probe = h->probe_enable ? *h->probe_enable : false;
    uint32_t c = 0;
    if (index)
        c |= CCR_LATCH_INDEX;
    if (probe && !index)
        c |= CCR_LATCH_PROBE;
    if (index || probe)
        c |= CCR_JUST_ONCE;
    if (h->probe_invert && *h->probe_invert)
        c |= CCR_PROBE_POL;
    if (h->index_invert)
        c |= CCR_INDEX_POL;
    if (h->index_mask)
        c |= CCR_INDEX_MASK;
    if (h->index_mask_invert)
        c |= CCR_INDEX_MASK_POL;
    if (h->counter_mode)
        c |= CCR_COUNTER_MODE;
    if (h->filter)
        c |= CCR_FILTER;
    /* quad error is write-1-to-clear: one write with bit 15 on the rising
     * edge of quad-error-enable */
    bool qe = *h->quad_error_enable;
    if (qe && !e->prev_qe_enable)
        c |= CCR_QUAD_ERROR;
    e->prev_qe_enable = qe;
    return c;
}

static void write_module_regs(hostmot2_t *hm2, bool force)
{
    struct hm2_encoder_state *s = hm2->encoder_s;
    uint32_t clock = s->md->clock_freq;
    bool hires = *s->ghal->hires_timestamp;
    if (force || hires != s->written_hires) {
        s->tsdiv = hm2_encoder_tsdiv(clock, hires);
        hm2_write_cfg(hm2, hm2_reg_addr(s->md, REG_TSDIV, 0), s->tsdiv);
        s->written_hires = hires;
    }
    uint32_t freq = *s->ghal->sample_frequency;
    if (force || freq != s->written_sample_frequency) {
        uint32_t eff;
        uint32_t rate = hm2_encoder_qfilter_rate(clock, freq, &eff);
        hm2_write_cfg(hm2, hm2_reg_addr(s->md, REG_QFILTER, 0), rate);
        *s->ghal->sample_frequency = eff;
        s->written_sample_frequency = eff;
    }
}

static void write_controls(hostmot2_t *hm2, bool force)
{
    struct hm2_encoder_state *s = hm2->encoder_s;
    for (int i = 0; i < s->num; i++) {
        struct enc_instance *e = &s->inst[i];
        uint32_t c = control_word(e);
        if (!force && e->control_written && c == e->written_control)
            continue;
        if (hm2_write_cfg(hm2, hm2_reg_addr(s->md, REG_CCR, i), c))
            continue;
        e->written_control = c;
        e->control_written = true;
        if (c & CCR_QUAD_ERROR)
            e->qe_armed = true;
        e->track.latch_pending = (c & CCR_LATCH_INDEX) != 0;
        e->track.probe_pending = (c & CCR_LATCH_PROBE) != 0;
    }
}

static void encoder_force_write(hostmot2_t *hm2)
{
    if (!hm2->encoder_s)
        return;
    write_module_regs(hm2, true);
    write_controls(hm2, true);
}

static void encoder_write_changed(hostmot2_t *hm2)
{
    if (!hm2->encoder_s)
        return;
    write_module_regs(hm2, false);
    write_controls(hm2, false);
}

static void encoder_process_read(hostmot2_t *hm2, long period)
{
    struct hm2_encoder_state *s = hm2->encoder_s;
    (void)period;
    if (!s)
        return;
    double tick = hm2_encoder_seconds_per_tsc(s->md->clock_freq, s->tsdiv);
    for (int i = 0; i < s->num; i++) {
        struct enc_instance *e = &s->inst[i];
        struct enc_hal *h = e->hal;
        struct hm2_encoder_sample smp = {s->count[i], s->ccr[i], (uint16_t)*s->tscount};
        if (!e->primed) {
            /* counts start at 0 whatever the counter holds at load */
            e->track.prev_reg_count = (uint16_t)smp.count_reg;
            e->primed = true;
        }
        if (fabs(h->scale) < 1e-6) {
            hm2_msg(hm2, HM2_ERR, "encoder.%02d.scale is too close to 0, setting it to 1.0", i);
            h->scale = 1.0;
        }
        bool probe_event;
        if (hm2_encoder_track_update(&e->track, &smp, h->scale, tick, h->vel_timeout,
                                     &probe_event))
            *h->index_enable = 0;
        /* hostmot2(9): probe-enable is reset to 0 when the latch happened */
        if (probe_event && h->probe_enable)
            *h->probe_enable = 0;
        if (*h->reset)
            e->track.zero_offset = e->track.rawcounts;
        *h->rawcounts = e->track.rawcounts;
        *h->rawlatch = e->track.rawlatch;
        *h->count = (int32_t)((uint32_t)e->track.rawcounts - (uint32_t)e->track.zero_offset);
        *h->count_latched = (int32_t)((uint32_t)e->track.rawlatch - (uint32_t)e->track.zero_offset);
        *h->position = *h->count / h->scale;
        *h->position_latched = *h->count_latched / h->scale;
        *h->velocity = e->track.velocity;
        *h->velocity_rpm = e->track.velocity * 60.0;
        *h->input_a = smp.ccr & 1u;
        *h->input_b = (smp.ccr >> 1) & 1u;
        *h->input_index = (smp.ccr >> 2) & 1u;
        /* an error from before quad-error-enable rose is stale: it is
         * cleared by the write that follows, so it is not reported */
        if (!*h->quad_error_enable)
            e->qe_armed = false;
        bool qe = (smp.ccr & CCR_QUAD_ERROR) && *h->quad_error_enable && e->qe_armed;
        if (qe && !*h->quad_error)
            hm2_msg(hm2, HM2_ERR, "Encoder %d: quadrature count error", i);
        *h->quad_error = qe;
    }
}

static void encoder_cleanup(hostmot2_t *hm2)
{
    if (hm2->encoder_s)
        free(hm2->encoder_s->inst);
    free(hm2->encoder_s);
    hm2->encoder_s = NULL;
}

const struct hm2_module_ops hm2_encoder_ops = {
    .name = "encoder",
    .setup = encoder_setup,
    .process_read = encoder_process_read,
    .write_changed = encoder_write_changed,
    .force_write = encoder_force_write,
    .cleanup = encoder_cleanup,
};
