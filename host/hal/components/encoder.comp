// SPDX-License-Identifier: GPL-2.0-or-later
//
// encoder: software counting of quadrature encoder signals, LinuxCNC 2.9's
// encoder (num_chan= or names=, up to 8 channels, its pins and its two
// module-wide functions; docs/encoder.md).  The counter is
// math/encoder_math.h; the channels' pins are made here in EXTRA_SETUP
// because 2.9 serves all channels with one update-counters and one
// capture-position function.
component encoder "Software counting of quadrature encoder signals";
function update_counters nofp "Samples the inputs and counts (run it in a fast thread)";
function capture_position "Publishes counts, position, velocity and latches";
variable int nchan;
variable enc_chan_t ch[8];
option singleton;
option rtapi_app no;
option extra_setup;
include "encoder_chan.h";
license "GPL";
;;
#define ENC_MAX_CHAN 8

static int num_chan;
RTAPI_MP_INT(num_chan, "number of encoder channels (default 3, at most 8)");
static char *names[ENC_MAX_CHAN];
RTAPI_MP_ARRAY_STRING(names, ENC_MAX_CHAN, "names of the encoder channels");

/* The channels' names, resolved before HAL is touched. */
static int cfg_nchan;
static char cfg_names[ENC_MAX_CHAN][HAL_NAME_LEN + 1];

#define ENC_PIN(kind, dir, field, suffix)                                             \
    if ((r = hal_pin_##kind##_newf(dir, &c->field, comp_id, "%s." suffix, name)) != 0) \
        return r

static int make_channel(enc_chan_t *c, const char *name)
{
    int r;
    ENC_PIN(bit, HAL_IN, phase_a, "phase-A");
    ENC_PIN(bit, HAL_IN, phase_b, "phase-B");
    ENC_PIN(bit, HAL_IN, phase_z, "phase-Z");
    ENC_PIN(bit, HAL_IO, index_enable, "index-enable");
    ENC_PIN(bit, HAL_IN, reset, "reset");
    ENC_PIN(bit, HAL_IN, latch_in, "latch-input");
    ENC_PIN(bit, HAL_IN, latch_rising, "latch-rising");
    ENC_PIN(bit, HAL_IN, latch_falling, "latch-falling");
    ENC_PIN(s32, HAL_OUT, rawcounts, "rawcounts");
    ENC_PIN(s32, HAL_OUT, counts, "counts");
    ENC_PIN(s32, HAL_OUT, counts_latched, "counts-latched");
    ENC_PIN(s32, HAL_IN, missing_teeth, "missing-teeth");
    ENC_PIN(float, HAL_OUT, position, "position");
    ENC_PIN(float, HAL_OUT, position_interp, "position-interpolated");
    ENC_PIN(float, HAL_OUT, position_latched, "position-latched");
    ENC_PIN(float, HAL_OUT, velocity, "velocity");
    ENC_PIN(float, HAL_OUT, velocity_rpm, "velocity-rpm");
    ENC_PIN(float, HAL_IO, position_scale, "position-scale");
    ENC_PIN(float, HAL_IN, min_speed, "min-speed-estimate");
    ENC_PIN(bit, HAL_IO, x4_mode, "x4-mode");
    ENC_PIN(bit, HAL_IO, counter_mode, "counter-mode");
    *c->latch_rising = 1;
    *c->latch_falling = 1;
    *c->position_scale = 1.0;
    *c->min_speed = 1.0;
    *c->x4_mode = 1;
    enc_init(&c->e);
    return 0;
}

EXTRA_SETUP() {
    nchan = cfg_nchan;
    for (int k = 0; k < cfg_nchan; k++) {
        int r = make_channel(&ch[k], cfg_names[k]);
        if (r != 0)
            return r;
    }
    return 0;
}

FUNCTION(update_counters) {
    for (int k = 0; k < nchan; k++) {
        enc_chan_t *c = &ch[k];
        enc_update(&c->e, *c->phase_a, *c->phase_b, *c->phase_z, *c->latch_in,
                   *c->latch_rising, *c->latch_falling, *c->x4_mode, *c->counter_mode, period);
        *c->rawcounts = c->e.raw;
    }
}

FUNCTION(capture_position) {
    for (int k = 0; k < nchan; k++) {
        enc_chan_t *c = &ch[k];
        bool index_enable = *c->index_enable;
        double scale = *c->position_scale;
        double min_speed = *c->min_speed;
        enc_capture(&c->e, &index_enable, &scale, &min_speed, *c->reset);
        if (!index_enable)
            *c->index_enable = 0;
        if (scale != *c->position_scale)
            *c->position_scale = scale;
        if (min_speed != *c->min_speed)
            *c->min_speed = min_speed;
        *c->counts = c->e.counts;
        *c->position = c->e.position;
        *c->position_interp = c->e.position_interp;
        *c->velocity = c->e.velocity;
        *c->velocity_rpm = c->e.velocity * 60.0;
        *c->counts_latched = c->e.counts_latched;
        *c->position_latched = c->e.position_latched;
    }
}

int rtapi_app_main(void) {
    if (num_chan < 0 || num_chan > ENC_MAX_CHAN) {
        rtapi_print_msg(RTAPI_MSG_ERR, "ENCODER: ERROR: invalid number of channels: %d\n",
                        num_chan);
        return -EINVAL;
    }
    bool named = names[0] != NULL && names[0][0] != '\0';
    int count = num_chan == 0 && !named ? 3 : num_chan;
    /* ".position-interpolated": the longest suffix of a channel's pins */
    int n = halcomp_instance_names("encoder", "encoder", "num_chan", count, ENC_MAX_CHAN, names,
                                   ENC_MAX_CHAN, 22, cfg_names);
    if (n < 0)
        return n;
    cfg_nchan = n;
    halcomp_args_t args = {0};
    return HALCOMP_LOAD(&args);
}

void rtapi_app_exit(void) {
    hal_exit(comp_id);
}
