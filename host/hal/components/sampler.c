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

#include "hal.h"
#include "halstream.h"
#include "rtapi.h"

typedef struct {
    halstream_chan_t c; /* enable, curr-depth, the data pins (IN), the FIFO */
    hal_bit_t *full;
    hal_s32_t *overruns;
    hal_s32_t *sample_num;
} sampler_t;

static void sample(void *arg, long period)
{
    sampler_t *s = arg;
    halstream_value_t vals[HALSTREAM_MAX_PINS];
    (void)period;
    if (!*s->c.enable)
        return;
    for (int i = 0; i < s->c.npins; i++)
        halstream_from_pin(s->c.types[i], s->c.pins[i], &vals[i]);
    rtapi_u32 num = (rtapi_u32)*s->sample_num;
    *s->sample_num = (rtapi_s32)(num + 1u);
    int r = halstream_write(&s->c.fifo, vals, num);
    /* simulated clock: wait for the reader while it is there */
    if (r == -ENOSPC && rtapi_is_simclock() && halstream_wait_peer(&s->c.fifo, 1))
        r = halstream_write(&s->c.fifo, vals, num);
    if (r != 0)
        (*s->overruns)++;
    int fill = halstream_fill(&s->c.fifo);
    *s->c.curr_depth = fill;
    *s->full = fill >= halstream_capacity(&s->c.fifo);
}

static int export_pins(void *chan, int comp_id, int n)
{
    sampler_t *s = chan;
    int r;
    if ((r = hal_pin_bit_newf(HAL_OUT, &s->full, comp_id, "sampler.%d.full", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_IO, &s->overruns, comp_id, "sampler.%d.overruns", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_IO, &s->sample_num, comp_id, "sampler.%d.sample-num", n)) < 0)
        return r;
    *s->full = 0;
    *s->overruns = 0;
    *s->sample_num = 0;
    return 0;
}

static const halstream_module_desc_t desc = {
    .name = "sampler", .who = "SAMPLER",
    .pin_dir = HAL_IN, .chan_size = sizeof(sampler_t),
    .export_pins = export_pins, .funct = sample,
};
HALSTREAM_MODULE(desc)

MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Realtime HAL sampler: pins to a FIFO read by halsampler");
