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
#include "hm_stream.h"
#include "rtapi.h"

#define MAX_CHAN HM_STREAM_MAX_CHAN

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
    hal_type_t types[HM_STREAM_MAX_PINS];
    void *pins[HM_STREAM_MAX_PINS];
    hm_stream_t fifo;
} sampler_t;

/* Module-level: the component id and the channel table that
 * rtapi_app_exit needs (the channels themselves live in HAL memory). */
static int comp_id;
static sampler_t *chans[MAX_CHAN];
static int nchan;

static void read_pin(const sampler_t *s, int i, hm_stream_value_t *v)
{
    memset(v, 0, sizeof(*v));
    switch (s->types[i]) {
    case HAL_BIT:
        v->b = *(hal_bit_t *)s->pins[i];
        break;
    case HAL_FLOAT:
        v->f = *(hal_float_t *)s->pins[i];
        break;
    case HAL_S32:
        v->s = *(hal_s32_t *)s->pins[i];
        break;
    case HAL_U32:
        v->u = *(hal_u32_t *)s->pins[i];
        break;
    case HAL_S64:
        v->ls = *(hal_s64_t *)s->pins[i];
        break;
    case HAL_U64:
        v->lu = *(hal_u64_t *)s->pins[i];
        break;
    default:
        break;
    }
}

static void sample(void *arg, long period)
{
    sampler_t *s = arg;
    hm_stream_value_t vals[HM_STREAM_MAX_PINS];
    (void)period;
    if (!*s->enable)
        return;
    for (int i = 0; i < s->npins; i++)
        read_pin(s, i, &vals[i]);
    rtapi_u32 num = (rtapi_u32)*s->sample_num;
    *s->sample_num = (rtapi_s32)(num + 1u);
    int r = hm_stream_write(&s->fifo, vals, num);
    if (r == -ENOSPC && rtapi_is_simclock()) {
        /* wait for the reader while it is there; virtual time stands still */
        unsigned spins = 0;
        while (r == -ENOSPC) {
            if ((spins++ % 64) == 0 && !hm_stream_peer_attached(&s->fifo))
                break;
            if (rtapi_sim_yield())
                break;
            r = hm_stream_write(&s->fifo, vals, num);
        }
    }
    if (r != 0)
        (*s->overruns)++;
    int fill = hm_stream_fill(&s->fifo);
    *s->curr_depth = fill;
    *s->full = fill >= hm_stream_capacity(&s->fifo);
}

static int count_strings(char **a, int max)
{
    int n = 0;
    while (n < max && a[n] != NULL && a[n][0] != '\0')
        n++;
    return n;
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
    r = hm_stream_create(&s->fifo, "sampler", n, depth[n], npins, types, err, sizeof(err));
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
            hm_stream_destroy(&chans[i]->fifo);
        chans[i] = NULL;
    }
}

int rtapi_app_main(void)
{
    hal_type_t types[MAX_CHAN][HM_STREAM_MAX_PINS];
    int npins[MAX_CHAN];
    char err[256];

    nchan = count_strings(cfg, MAX_CHAN);
    if (nchan == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SAMPLER: ERROR: no channels specified (cfg= missing)\n");
        return -EINVAL;
    }
    /* Validate everything before creating anything. */
    for (int n = nchan; n < MAX_CHAN; n++) {
        if (cfg[n] != NULL && cfg[n][0] != '\0') {
            rtapi_print_msg(RTAPI_MSG_ERR, "SAMPLER: ERROR: cfg string %d is empty\n", nchan);
            return -EINVAL;
        }
        if (depth[n] != 0) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "SAMPLER: ERROR: depth given for channel %d but only %d cfg "
                            "string(s)\n",
                            n, nchan);
            return -EINVAL;
        }
    }
    for (int n = 0; n < nchan; n++) {
        if (depth[n] <= 0) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "SAMPLER: ERROR: channel %d (cfg=%s): depth missing or not "
                            "positive (%d)\n",
                            n, cfg[n], depth[n]);
            return -EINVAL;
        }
        npins[n] = hm_stream_parse_cfg(cfg[n], types[n], err, sizeof(err));
        if (npins[n] < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "SAMPLER: ERROR: channel %d: bad cfg '%s': %s\n", n,
                            cfg[n], err);
            return -EINVAL;
        }
    }
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
