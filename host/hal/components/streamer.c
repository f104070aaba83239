/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * streamer - write data from a FIFO, filled by halstreamer(1), to HAL
 * pins in realtime.
 *
 *   loadrt streamer depth=D0[,D1...] cfg=C0[,C1...]
 *
 * One channel per cfg string (at most 8); cfg characters b f s u (bit,
 * float, s32, u32; upper case too; l and k for s64/u64 are our extension),
 * at most 21 per channel.  Channel N has, as LinuxCNC 2.9:
 *   pins streamer.N.pin.M (OUT, typed by cfg), streamer.N.enable (bit IN,
 *   default TRUE), streamer.N.curr-depth (s32 OUT), streamer.N.empty (bit
 *   OUT, TRUE until the first run), streamer.N.underruns (s32 I/O),
 *   streamer.N.clock (bit IN), streamer.N.clock-mode (s32 IN);
 *   function streamer.N (floating point).
 *
 * Each period (behaviour observed on 2.9): curr-depth and empty are set
 * from the FIFO level first, even when disabled; then, if enabled and
 * clocked (clock-mode 0 or any other value: every period; 1: falling edge
 * of clock; 2: rising edge; 3: any edge), one sample is moved to the pins,
 * or, if the FIFO is empty, underruns is incremented and the pins keep
 * their values.
 *
 * Simulated clock (HAL_SIMCLOCK): while a halstreamer is attached, a
 * clocked period that finds the FIFO empty waits for it (rtapi_sim_yield
 * keeps virtual time still) instead of underrunning, so a simulated run
 * is deterministic.
 *
 * Configuration errors fail the load and leave nothing behind.  See
 * docs/streamer.md.
 */
#include "hal.h"
#include "halstream.h"
#include "rtapi.h"

typedef struct {
    halstream_chan_t c; /* enable, curr-depth, the data pins (OUT), the FIFO */
    hal_bit_t *empty;
    hal_s32_t *underruns;
    hal_bit_t *clock;
    hal_s32_t *clock_mode;
    int last_clock;
} streamer_t;

static int clocked(streamer_t *s)
{
    int clk = *s->clock ? 1 : 0;
    int rising = clk && !s->last_clock;
    int falling = !clk && s->last_clock;
    s->last_clock = clk;
    switch (*s->clock_mode) {
    case 1:
        return falling;
    case 2:
        return rising;
    case 3:
        return rising || falling;
    default:
        return 1;
    }
}

static void update(void *arg, long period)
{
    streamer_t *s = arg;
    halstream_value_t vals[HALSTREAM_MAX_PINS];
    (void)period;
    int doclk = clocked(s);
    int want = *s->c.enable && doclk;
    /* simulated clock: wait for the writer while it is there */
    if (want && rtapi_is_simclock() && halstream_fill(&s->c.fifo) == 0)
        halstream_wait_peer(&s->c.fifo, 0);
    int fill = halstream_fill(&s->c.fifo);
    *s->c.curr_depth = fill;
    *s->empty = fill == 0;
    if (!want)
        return;
    if (halstream_read(&s->c.fifo, vals, NULL) != 0) {
        (*s->underruns)++;
        return;
    }
    for (int i = 0; i < s->c.npins; i++)
        halstream_to_pin(s->c.types[i], s->c.pins[i], &vals[i]);
}

static int export_pins(void *chan, int comp_id, int n)
{
    streamer_t *s = chan;
    int r;
    if ((r = hal_pin_bit_newf(HAL_OUT, &s->empty, comp_id, "streamer.%d.empty", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_IO, &s->underruns, comp_id, "streamer.%d.underruns", n)) < 0 ||
        (r = hal_pin_bit_newf(HAL_IN, &s->clock, comp_id, "streamer.%d.clock", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_IN, &s->clock_mode, comp_id, "streamer.%d.clock-mode", n)) < 0)
        return r;
    *s->empty = 1;
    *s->underruns = 0;
    *s->clock = 0;
    *s->clock_mode = 0;
    return 0;
}

static const halstream_module_desc_t desc = {
    .name = "streamer", .who = "STREAMER",
    .pin_dir = HAL_OUT, .chan_size = sizeof(streamer_t),
    .export_pins = export_pins, .funct = update,
};
HALSTREAM_MODULE(desc)

MODULE_LICENSE("GPL");
MODULE_DESCRIPTION("Realtime HAL streamer: a FIFO filled by halstreamer to pins");
