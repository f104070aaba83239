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
    hal_bit_t *empty;
    hal_s32_t *underruns;
    hal_bit_t *clock;
    hal_s32_t *clock_mode;
    int last_clock;
    int npins;
    hal_type_t types[HALSTREAM_MAX_PINS];
    void *pins[HALSTREAM_MAX_PINS];
    halstream_t fifo;
} streamer_t;

/* Module-level: the component id and the channel table rtapi_app_exit
 * needs (the channels themselves live in HAL memory). */
static int comp_id;
static streamer_t *chans[MAX_CHAN];

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
    int want = *s->enable && doclk;
    /* simulated clock: wait for the writer while it is there */
    if (want && rtapi_is_simclock() && halstream_fill(&s->fifo) == 0)
        halstream_wait_peer(&s->fifo, 0);
    int fill = halstream_fill(&s->fifo);
    *s->curr_depth = fill;
    *s->empty = fill == 0;
    if (!want)
        return;
    if (halstream_read(&s->fifo, vals, NULL) != 0) {
        (*s->underruns)++;
        return;
    }
    for (int i = 0; i < s->npins; i++)
        halstream_to_pin(s->types[i], s->pins[i], &vals[i]);
}

static int init_channel(int n, const hal_type_t *types, int npins)
{
    char err[256];
    streamer_t *s = hal_malloc(sizeof(*s));
    if (s == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "STREAMER: ERROR: out of HAL memory for channel %d\n", n);
        return -ENOMEM;
    }
    memset(s, 0, sizeof(*s));
    int r;
    if ((r = hal_pin_bit_newf(HAL_IN, &s->enable, comp_id, "streamer.%d.enable", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_OUT, &s->curr_depth, comp_id, "streamer.%d.curr-depth", n)) <
            0 ||
        (r = hal_pin_bit_newf(HAL_OUT, &s->empty, comp_id, "streamer.%d.empty", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_IO, &s->underruns, comp_id, "streamer.%d.underruns", n)) < 0 ||
        (r = hal_pin_bit_newf(HAL_IN, &s->clock, comp_id, "streamer.%d.clock", n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_IN, &s->clock_mode, comp_id, "streamer.%d.clock-mode", n)) < 0)
        return r;
    *s->enable = 1;
    *s->curr_depth = 0;
    *s->empty = 1;
    *s->underruns = 0;
    *s->clock = 0;
    *s->clock_mode = 0;
    s->npins = npins;
    for (int i = 0; i < npins; i++) {
        s->types[i] = types[i];
        r = hal_pin_newf(types[i], HAL_OUT, &s->pins[i], comp_id, "streamer.%d.pin.%d", n, i);
        if (r < 0)
            return r;
    }
    r = halstream_create(&s->fifo, "streamer", n, depth[n], npins, types, err, sizeof(err));
    if (r < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "STREAMER: ERROR: channel %d: %s\n", n, err);
        return r;
    }
    chans[n] = s;
    return hal_export_functf(update, s, 1, 0, comp_id, "streamer.%d", n);
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
    int nchan = halstream_check_params("STREAMER", cfg, depth, MAX_CHAN, types, npins);
    if (nchan < 0)
        return nchan;
    comp_id = hal_init("streamer");
    if (comp_id < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "STREAMER: ERROR: hal_init() failed\n");
        return comp_id;
    }
    for (int n = 0; n < nchan; n++) {
        int r = init_channel(n, types[n], npins[n]);
        if (r < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "STREAMER: ERROR: channel %d failed (%d), nothing of streamer was "
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
MODULE_DESCRIPTION("Realtime HAL streamer: a FIFO filled by halstreamer to pins");
