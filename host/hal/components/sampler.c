/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * sampler - sample HAL pins in realtime into a FIFO that halsampler(1)
 * copies to a file.
 *
 *   loadrt sampler depth=D0[,D1...] cfg=C0[,C1...]
 *
 * One channel per cfg string (at most 8); cfg characters b f s u (bit,
 * float, s32, u32; upper case too; l and k for s64/u64 are our extension),
 * at most 21 per channel; depth = FIFO size in samples.  Channel N has, as
 * LinuxCNC 2.9:
 *   pins sampler.N.pin.M (IN, typed by cfg), sampler.N.enable (bit IN,
 *   default TRUE), sampler.N.curr-depth (s32 OUT), sampler.N.full (bit
 *   OUT), sampler.N.overruns and sampler.N.sample-num (s32 I/O);
 *   function sampler.N (floating point).
 *
 * Each period, while enable is TRUE, the pin values are stored with the
 * current sample-num, and sample-num is incremented; when the FIFO is full
 * the sample is dropped and overruns is incremented, so halsampler sees a
 * gap in the sample numbers (LinuxCNC 2.9 leaves sample-num at 0 and only
 * numbers stored samples; we follow its man page, which documents the
 * behaviour above).  curr-depth and full are updated after the write.
 *
 * Simulated clock (HAL_SIMCLOCK): while a halsampler is attached, a full
 * FIFO makes the function wait for it (rtapi_sim_yield keeps virtual time
 * still) instead of dropping, so a simulated run is deterministic.
 *
 * Unlike 2.9, every configuration error fails the load and leaves nothing
 * behind: a bad cfg character, a depth missing or 0, more depths than cfg
 * strings.  See docs/sampler.md.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "hal.h"
#include "halstream.h"
#include "rtapi.h"

#define MAX_CHAN HALSTREAM_MAX_CHAN

static int depth[MAX_CHAN];
RTAPI_MP_ARRAY_INT(depth, MAX_CHAN, "fifo depth (samples) of each channel");
static char *cfg[MAX_CHAN];
RTAPI_MP_ARRAY_STRING(cfg, MAX_CHAN, "config string of each channel (b f s u)");

typedef struct {
    hal_bit_t *enable;
    hal_s32_t *curr_depth;
    hal_bit_t *full;
    hal_s32_t *overruns;
    hal_s32_t *sample_num;
    int npins;
    hal_type_t types[HALSTREAM_MAX_PINS];
    void *pins[HALSTREAM_MAX_PINS];
    halstream_t fifo;
} sampler_t;

/* Module-level: the component id and the channel table that
 * rtapi_app_exit needs (the channels themselves live in HAL memory). */
static int comp_id;
static sampler_t *chans[MAX_CHAN];
static int nchan;

static void sample(void *arg, long period)
{
    sampler_t *s = arg;
    halstream_value_t vals[HALSTREAM_MAX_PINS];
    (void)period;
    if (!*s->enable)
        return;
    for (int i = 0; i < s->npins; i++)
        halstream_from_pin(s->types[i], s->pins[i], &vals[i]);
    rtapi_u32 num = (rtapi_u32)*s->sample_num;
    *s->sample_num = (rtapi_s32)(num + 1u);
    int r = halstream_write(&s->fifo, vals, num);
    /* simulated clock: wait for the reader while it is there */
    if (r == -ENOSPC && rtapi_is_simclock() && halstream_wait_peer(&s->fifo, 1))
        r = halstream_write(&s->fifo, vals, num);
    if (r != 0)
        (*s->overruns)++;
    int fill = halstream_fill(&s->fifo);
    *s->curr_depth = fill;
    *s->full = fill >= halstream_capacity(&s->fifo);
}

static int init_channel(int n, const hal_type_t *types, int npins)
{
    char err[256];
    sampler_t *s = hal_malloc(sizeof(*s));
    if (s == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SAMPLER: ERROR: out of HAL memory for channel %d\n", n);
        return -ENOMEM;
    }
    memset(s, 0, sizeof(*s));
    int r;
    if ((r = hal_pin_bit_newf(HAL_IN, &s->enable, comp_id, "sampler.%d.enable", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_OUT, &s->curr_depth, comp_id, "sampler.%d.curr-depth", n)) < 0 ||
        (r = hal_pin_bit_newf(HAL_OUT, &s->full, comp_id, "sampler.%d.full", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_IO, &s->overruns, comp_id, "sampler.%d.overruns", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_IO, &s->sample_num, comp_id, "sampler.%d.sample-num", n)) < 0)
        return r;
    *s->enable = 1;
    *s->curr_depth = 0;
    *s->full = 0;
    *s->overruns = 0;
    *s->sample_num = 0;
    s->npins = npins;
    for (int i = 0; i < npins; i++) {
        s->types[i] = types[i];
        r = hal_pin_newf(types[i], HAL_IN, &s->pins[i], comp_id, "sampler.%d.pin.%d", n, i);
        if (r < 0)
            return r;
    }
    r = halstream_create(&s->fifo, "sampler", n, depth[n], npins, types, err, sizeof(err));
    if (r < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SAMPLER: ERROR: channel %d: %s\n", n, err);
        return r;
    }
    chans[n] = s;
    r = hal_export_functf(sample, s, 1, 0, comp_id, "sampler.%d", n);
    if (r < 0)
        return r;
    return 0;
}

static void destroy_channels(void)
{
    for (int i = 0; i < MAX_CHAN; i++) {
        if (chans[i] != NULL)
            halstream_destroy(&chans[i]->fifo);
        chans[i] = NULL;
    }
}

int rtapi_app_main(void)
{
    hal_type_t types[MAX_CHAN][HALSTREAM_MAX_PINS];
    int npins[MAX_CHAN];

    /* Validate everything before creating anything. */
    nchan = halstream_check_params("SAMPLER", cfg, depth, MAX_CHAN, types, npins);
    if (nchan < 0)
        return nchan;
    comp_id = hal_init("sampler");
    if (comp_id < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SAMPLER: ERROR: hal_init() failed\n");
        return comp_id;
    }
    for (int n = 0; n < nchan; n++) {
        int r = init_channel(n, types[n], npins[n]);
        if (r < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "SAMPLER: ERROR: channel %d failed (%d), nothing of sampler was "
                            "kept\n",
                            n, r);
            destroy_channels();
            hal_exit(comp_id);
            return r;
        }
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    destroy_channels();
    hal_exit(comp_id);
}

MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Realtime HAL sampler: pins to a FIFO read by halsampler");
