/* SPDX-License-Identifier: GPL-2.0-or-later */
/* StepGen (spec §9.4, §10.1): position/velocity control computing the
 * rate register every period, feedback from the 16.16 accumulator, timing
 * registers from ns parameters, output mode and step tables. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "module_api.h"

enum {
    REG_RATE = 0,
    REG_ACCUM = 1,
    REG_MODE = 2,
    REG_DIRSETUP = 3,
    REG_DIRHOLD = 4,
    REG_STEPLEN = 5,
    REG_STEPSPACE = 6,
    REG_TABLEDATA = 7,
    REG_TABLELEN = 8,
    REG_MASTERDDS = 9,
};

struct sg_hal {
    hal_float_t *position_cmd, *velocity_cmd, *position_fb, *velocity_fb;
    hal_s32_t *counts, *dbg_step_rate;
    hal_bit_t *enable, *control_type, *position_reset;
    hal_float_t *dbg_pos_minus_prev_cmd, *dbg_ff_vel, *dbg_s_to_match, *dbg_vel_error,
        *dbg_err_at_match;
    hal_float_t position_scale, maxvel, maxaccel;
    hal_u32_t steplen, stepspace, dirsetup, dirhold, step_type;
    hal_u32_t table_data[4];
    hal_bit_t swap_step_dir;
};

struct sg_instance {
    struct sg_hal *hal;
    bool primed;
    uint32_t prev_accumulator;
    int64_t subcounts;
    double old_position_cmd;
    /* last written */
    uint32_t w_timing[4]; /* ns values, order REG_DIRSETUP..REG_STEPSPACE */
    bool timing_written;
    uint32_t w_step_type, w_table[4];
    bool w_swap, mode_written;
};

struct hm2_stepgen_state {
    const struct hm2_md *md;
    int num;
    bool has_swap;
    struct sg_instance *inst;
    uint32_t *accum; /* TRAM read */
    uint32_t *rate;  /* TRAM write */
};

static int export_instance(hostmot2_t *hm2, int i, struct sg_hal *h, bool swap)
{
    const char *pfx = hm2->llio->name;
    int id = hm2->llio->comp_id, r = 0;
    char what[48];
    snprintf(what, sizeof(what), "stepgen.%02d", i);
#define PIN(kind, dir, field, nm) \
    if (!r) r = hal_pin_##kind##_newf(dir, &h->field, id, "%s.stepgen.%02d." nm, pfx, i)
#define PAR(kind, field, nm) \
    if (!r) r = hal_param_##kind##_newf(HAL_RW, &h->field, id, "%s.stepgen.%02d." nm, pfx, i)
    PIN(float, HAL_IN, position_cmd, "position-cmd");
    PIN(float, HAL_IN, velocity_cmd, "velocity-cmd");
    PIN(float, HAL_OUT, position_fb, "position-fb");
    PIN(float, HAL_OUT, velocity_fb, "velocity-fb");
    PIN(s32, HAL_OUT, counts, "counts");
    PIN(bit, HAL_IN, enable, "enable");
    PIN(bit, HAL_IN, control_type, "control-type");
    PIN(bit, HAL_IN, position_reset, "position-reset");
    PIN(float, HAL_OUT, dbg_pos_minus_prev_cmd, "dbg_pos_minus_prev_cmd");
    PIN(float, HAL_OUT, dbg_ff_vel, "dbg_ff_vel");
    PIN(float, HAL_OUT, dbg_s_to_match, "dbg_s_to_match");
    PIN(float, HAL_OUT, dbg_vel_error, "dbg_vel_error");
    PIN(float, HAL_OUT, dbg_err_at_match, "dbg_err_at_match");
    PIN(s32, HAL_OUT, dbg_step_rate, "dbg_step_rate");
    PAR(float, position_scale, "position-scale");
    PAR(float, maxvel, "maxvel");
    PAR(float, maxaccel, "maxaccel");
    PAR(u32, steplen, "steplen");
    PAR(u32, stepspace, "stepspace");
    PAR(u32, dirsetup, "dirsetup");
    PAR(u32, dirhold, "dirhold");
    PAR(u32, step_type, "step_type");
    if (swap)
        PAR(bit, swap_step_dir, "swap_step_dir");
    for (int t = 0; t < 4 && !r; t++)
        r = hal_param_u32_newf(HAL_RW, &h->table_data[t], id, "%s.stepgen.%02d.table-data-%d",
                               pfx, i, t);
#undef PIN
#undef PAR
    if (r)
        return hm2_hal_fail(hm2, r, what);
    *h->position_cmd = *h->velocity_cmd = *h->position_fb = *h->velocity_fb = 0.0;
    *h->counts = *h->dbg_step_rate = 0;
    *h->enable = *h->control_type = *h->position_reset = 0;
    *h->dbg_pos_minus_prev_cmd = *h->dbg_ff_vel = *h->dbg_s_to_match = 0.0;
    *h->dbg_vel_error = *h->dbg_err_at_match = 0.0;
    h->position_scale = 1.0;
    h->maxvel = 0.0;
    h->maxaccel = 1.0;
    uint32_t def = (uint32_t)hm2_stepgen_clocks_to_ns(0x3FFF, hm2->stepgen.md.clock_freq);
    h->steplen = h->stepspace = h->dirsetup = h->dirhold = def;
    h->step_type = 0;
    h->swap_step_dir = 0;
    return 0;
}

static int stepgen_setup(hostmot2_t *hm2)
{
    if (!hm2->stepgen.present || hm2->stepgen.used == 0)
        return 0;
    struct hm2_stepgen_state *s = calloc(1, sizeof(*s));
    if (!s) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating stepgen state");
        return -ENOMEM;
    }
    hm2->stepgen_s = s;
    s->md = &hm2->stepgen.md;
    s->num = hm2->stepgen.used;
    s->has_swap = s->md->version == 0x42 || s->md->version == 0xC2;
    s->inst = calloc((size_t)s->num, sizeof(*s->inst));
    struct sg_hal *h = hm2_hal_zalloc(hm2, sizeof(*h) * (size_t)s->num, "stepgen pins");
    if (!s->inst || !h) {
        if (!s->inst)
            hm2_msg(hm2, HM2_ERR, "out of memory allocating stepgen instances");
        return -ENOMEM;
    }
    int r;
    for (int i = 0; i < s->num; i++) {
        s->inst[i].hal = &h[i];
        if ((r = export_instance(hm2, i, &h[i], s->has_swap)))
            return r;
    }
    if ((r = hm2_tram_add_read(hm2, hm2_reg_addr(s->md, REG_ACCUM, 0), &s->accum, s->num)) ||
        (r = hm2_tram_add_write(hm2, hm2_reg_addr(s->md, REG_RATE, 0), &s->rate, s->num)))
        return r;
    return 0;
}

static void stepgen_process_read(hostmot2_t *hm2, long period)
{
    struct hm2_stepgen_state *s = hm2->stepgen_s;
    (void)period;
    if (!s)
        return;
    for (int i = 0; i < s->num; i++) {
        struct sg_instance *g = &s->inst[i];
        struct sg_hal *h = g->hal;
        uint32_t acc = s->accum[i];
        if (!g->primed) {
            g->prev_accumulator = acc; /* feedback starts at 0 */
            g->subcounts = 0;
            g->primed = true;
        }
        g->subcounts = hm2_stepgen_accumulate(g->subcounts, g->prev_accumulator, acc);
        g->prev_accumulator = acc;
        if (*h->position_reset)
            g->subcounts = 0;
        if (fabs(h->position_scale) < 1e-6) {
            hm2_msg(hm2, HM2_ERR,
                    "stepgen.%02d.position-scale is too close to 0, setting it to %s1.0", i,
                    h->position_scale < 0 ? "-" : "");
            h->position_scale = h->position_scale < 0 ? -1.0 : 1.0;
        }
        *h->counts = (int32_t)(g->subcounts >> 16);
        *h->position_fb = ((double)g->subcounts / 65536.0) / h->position_scale;
    }
}

/* LinuxCNC 2.9 takes a negative maxaccel as its absolute value (a negative
 * limit would otherwise flip the ramp direction and the position would run
 * away). */
static void sanitize_maxaccel(hostmot2_t *hm2, int i, struct sg_hal *h)
{
    if (h->maxaccel < 0.0) {
        hm2_msg(hm2, HM2_ERR, "stepgen.%02d.maxaccel < 0, setting to its absolute value", i);
        h->maxaccel = -h->maxaccel;
    }
}

static double effective_maxvel(hostmot2_t *hm2, int i, struct sg_hal *h)
{
    double physical = hm2_stepgen_physical_maxvel(h->steplen, h->stepspace, h->position_scale);
    if (h->maxvel < 0.0) {
        hm2_msg(hm2, HM2_ERR, "stepgen.%02d.maxvel < 0, setting to its absolute value", i);
        h->maxvel = -h->maxvel;
    }
    if (h->maxvel == 0.0)
        return physical;
    if (physical > 0.0 && h->maxvel > physical) {
        hm2_msg(hm2, HM2_ERR,
                "stepgen.%02d.maxvel is too big for current step timings & position-scale, "
                "clipping to max possible (%.6g)",
                i, physical);
        h->maxvel = physical;
    }
    return h->maxvel;
}

static void stepgen_prepare_write(hostmot2_t *hm2, long period)
{
    struct hm2_stepgen_state *s = hm2->stepgen_s;
    if (!s)
        return;
    double T = (double)period * 1e-9;
    for (int i = 0; i < s->num; i++) {
        struct sg_instance *g = &s->inst[i];
        struct sg_hal *h = g->hal;
        double maxvel = effective_maxvel(hm2, i, h);
        sanitize_maxaccel(hm2, i, h);
        if (!*h->enable || T <= 0.0) {
            s->rate[i] = 0;
            *h->velocity_fb = 0.0;
            *h->dbg_step_rate = 0;
            g->old_position_cmd = *h->position_cmd;
            continue;
        }
        double vcmd;
        if (*h->control_type) {
            vcmd = hm2_stepgen_velocity_control(*h->velocity_cmd, *h->velocity_fb, h->maxaccel, T);
        } else {
            struct hm2_stepgen_posctl p = {
                .position_cmd = *h->position_cmd,
                .position_fb = *h->position_fb,
                .velocity_fb = *h->velocity_fb,
                .maxaccel = h->maxaccel,
                .period_s = T,
                .old_position_cmd = g->old_position_cmd,
            };
            vcmd = hm2_stepgen_position_control(&p);
            g->old_position_cmd = p.old_position_cmd;
            *h->dbg_pos_minus_prev_cmd = p.dbg_pos_minus_prev_cmd;
            *h->dbg_ff_vel = p.dbg_ff_vel;
            *h->dbg_vel_error = p.dbg_vel_error;
            *h->dbg_s_to_match = p.dbg_s_to_match;
            *h->dbg_err_at_match = p.dbg_err_at_match;
        }
        if (maxvel > 0.0) {
            if (vcmd > maxvel)
                vcmd = maxvel;
            else if (vcmd < -maxvel)
                vcmd = -maxvel;
        }
        *h->velocity_fb = vcmd;
        s->rate[i] = hm2_stepgen_rate_register(vcmd, h->position_scale, s->md->clock_freq);
        *h->dbg_step_rate = (int32_t)s->rate[i];
    }
}

static void write_reg(hostmot2_t *hm2, int reg, int inst, uint32_t v)
{
    hm2_write_cfg(hm2, hm2_reg_addr(hm2->stepgen_s->md, reg, inst), v);
}

static void write_timing(hostmot2_t *hm2, int i, bool force)
{
    struct sg_instance *g = &hm2->stepgen_s->inst[i];
    struct sg_hal *h = g->hal;
    static const char *const names[4] = {"dirsetup", "dirhold", "steplen", "stepspace"};
    hal_u32_t *ns[4] = {&h->dirsetup, &h->dirhold, &h->steplen, &h->stepspace};
    uint32_t clock = hm2->stepgen_s->md->clock_freq;
    for (int k = 0; k < 4; k++) {
        if (!force && g->timing_written && *ns[k] == g->w_timing[k])
            continue;
        bool clipped;
        uint32_t clocks = hm2_stepgen_ns_to_clocks(*ns[k], clock, &clipped);
        if (clipped) {
            uint32_t max = (uint32_t)hm2_stepgen_clocks_to_ns(clocks, clock);
            hm2_msg(hm2, HM2_ERR,
                    "stepgen.%02d.%s %u ns is longer than the firmware allows (16383 clocks), "
                    "clipping to %u ns",
                    i, names[k], (unsigned)*ns[k], max);
            *ns[k] = max;
        }
        write_reg(hm2, REG_DIRSETUP + k, i, clocks);
        g->w_timing[k] = *ns[k];
    }
    g->timing_written = true;
}

static void write_mode(hostmot2_t *hm2, int i, bool force)
{
    struct hm2_stepgen_state *s = hm2->stepgen_s;
    struct sg_instance *g = &s->inst[i];
    struct sg_hal *h = g->hal;
    bool swap = s->has_swap && h->swap_step_dir;
    bool tables_same = true;
    for (int t = 0; t < 4; t++)
        tables_same = tables_same && h->table_data[t] == g->w_table[t];
    if (!force && g->mode_written && h->step_type == g->w_step_type && swap == g->w_swap &&
        (h->step_type < 3 || tables_same))
        return;
    uint32_t flags = swap ? (1u << 2) : 0;
    uint32_t st = h->step_type;
    if (st > 16) {
        hm2_msg(hm2, HM2_ERR,
                "stepgen.%02d.step_type %u is invalid (0-2, or 3-16 for a step table of that "
                "length), using 0 (step/dir)",
                i, (unsigned)st);
        st = 0;
        h->step_type = 0;
    }
    if (st < 3) {
        write_reg(hm2, REG_MODE, i, st | flags);
    } else {
        /* table entries last first, one byte of table-data per entry */
        for (int j = (int)st - 1; j >= 0; j--)
            write_reg(hm2, REG_TABLEDATA, i, (h->table_data[j / 4] >> (8 * (j % 4))) & 0xFF);
        write_reg(hm2, REG_TABLELEN, i, st - 1);
        write_reg(hm2, REG_MODE, i, 3u | flags);
    }
    g->w_step_type = h->step_type;
    g->w_swap = swap;
    for (int t = 0; t < 4; t++)
        g->w_table[t] = h->table_data[t];
    g->mode_written = true;
}

static void stepgen_write_changed(hostmot2_t *hm2)
{
    struct hm2_stepgen_state *s = hm2->stepgen_s;
    if (!s)
        return;
    for (int i = 0; i < s->num; i++) {
        write_timing(hm2, i, false);
        write_mode(hm2, i, false);
    }
}

static void stepgen_force_write(hostmot2_t *hm2)
{
    struct hm2_stepgen_state *s = hm2->stepgen_s;
    if (!s)
        return;
    for (int i = 0; i < s->num; i++) {
        write_timing(hm2, i, true);
        if (!s->inst[i].mode_written)
            write_mode(hm2, i, true);
    }
    write_reg(hm2, REG_MASTERDDS, 0, 0xFFFFFFFFu);
}

static void stepgen_cleanup(hostmot2_t *hm2)
{
    if (hm2->stepgen_s)
        free(hm2->stepgen_s->inst);
    free(hm2->stepgen_s);
    hm2->stepgen_s = NULL;
}

const struct hm2_module_ops hm2_stepgen_ops = {
    .name = "stepgen",
    .setup = stepgen_setup,
    .process_read = stepgen_process_read,
    .prepare_write = stepgen_prepare_write,
    .write_changed = stepgen_write_changed,
    .force_write = stepgen_force_write,
    .cleanup = stepgen_cleanup,
};
