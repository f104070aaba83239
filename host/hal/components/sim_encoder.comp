// SPDX-License-Identifier: GPL-2.0-or-later
//
// sim_encoder: quadrature and index signals of a simulated encoder, LinuxCNC
// 2.9's sim_encoder (num_chan= or names=, up to 8 channels, one make-pulses
// and one update-speed function for all channels; docs/sim_encoder.md).
//
// update-speed turns speed into a signed 32-bit phase increment per
// make-pulses period; make-pulses adds it to a 32-bit phase and takes one
// quadrature step (up or down by the increment's sign) each time the
// phase's top bit changes, so one step per period is the top rate.
component sim_encoder "Simulated quadrature encoder";
function make_pulses nofp "Step the quadrature outputs of every channel (run it fast)";
function update_speed "Turn speed, scale and ppr into each channel's step rate";
variable int nchan;
variable se_chan_t ch[8];
option singleton;
option rtapi_app no;
option extra_setup;
include "sim_encoder_chan.h";
license "GPL";
;;
#define SE_MAX_CHAN 8

static int num_chan;
RTAPI_MP_INT(num_chan, "number of simulated encoders (default 1, at most 8)");
static char *names[SE_MAX_CHAN];
RTAPI_MP_ARRAY_STRING(names, SE_MAX_CHAN, "names of the simulated encoders");

static int cfg_nchan;
static char cfg_names[SE_MAX_CHAN][HAL_NAME_LEN + 1];

/* make-pulses' period, read by update-speed; 50 us until make-pulses ran
 * (2.9's assumption, so a speed set before the first period moves at once) */
static long pulse_period_ns = 50000;
static long rate_period_ns;
static double max_rate;   /* steps per second: one per make-pulses period */
static double phase_gain; /* phase increment per (step per second) */

#define SE_PIN(kind, dir, field, suffix)                                              \
    if ((r = hal_pin_##kind##_newf(dir, &c->field, comp_id, "%s." suffix, name)) != 0) \
        return r

static int make_channel(se_chan_t *c, const char *name)
{
    int r;
    SE_PIN(u32, HAL_IO, ppr, "ppr");
    SE_PIN(float, HAL_IO, scale, "scale");
    SE_PIN(s32, HAL_IN, rawcounts, "rawcounts");
    SE_PIN(float, HAL_IN, speed, "speed");
    SE_PIN(bit, HAL_OUT, phase_a, "phase-A");
    SE_PIN(bit, HAL_OUT, phase_b, "phase-B");
    SE_PIN(bit, HAL_OUT, phase_z, "phase-Z");
    *c->ppr = 100;
    *c->scale = 1.0;
    c->last_scale = 1.0;
    c->inv_scale = 1.0;
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

/* The phase increment as 2.9 stores it: converted through 64 bits and cut
 * to 32, so a full-rate command (2^31) comes out negative and a NaN as 0. */
static int32_t se_increment(double x)
{
    int64_t wide = (x == x && fabs(x) < 9223372036854775808.0) ? (int64_t)x : INT64_MIN;
    return (int32_t)(uint32_t)(uint64_t)wide;
}

FUNCTION(update_speed) {
    if (pulse_period_ns != rate_period_ns) {
        rate_period_ns = pulse_period_ns;
        max_rate = 1.0e9 / (double)pulse_period_ns;
        phase_gain = 2147483648.0 / max_rate;
    }
    for (int k = 0; k < nchan; k++) {
        se_chan_t *c = &ch[k];
        if (*c->scale != c->last_scale) {
            c->last_scale = *c->scale;
            // a scale of (almost) 0 is replaced by 1
            if (*c->scale > -1e-20 && *c->scale < 1e-20)
                *c->scale = 1.0;
            c->inv_scale = 1.0 / *c->scale;
        }
        double rate = *c->speed * c->inv_scale * (double)*c->ppr * 4.0;
        if (rate > max_rate)
            rate = max_rate;
        else if (rate < -max_rate)
            rate = -max_rate;
        c->increment = se_increment(rate * phase_gain);
    }
}

FUNCTION(make_pulses) {
    pulse_period_ns = period;
    for (int k = 0; k < nchan; k++) {
        se_chan_t *c = &ch[k];
        uint32_t before = c->phase;
        c->phase += (uint32_t)c->increment;
        if ((before ^ c->phase) & 0x80000000u) {
            if (c->increment > 0) {
                if (++c->quad > 3) {
                    c->quad = 0;
                    if ((hal_u32_t)++c->pulse >= *c->ppr)
                        c->pulse = 0;
                }
                *c->rawcounts += 1;
            } else {
                if (--c->quad < 0) {
                    c->quad = 3;
                    if (--c->pulse < 0)
                        c->pulse = (int)(*c->ppr - 1);
                }
                *c->rawcounts -= 1;
            }
        }
        // quadrature: 0 = A high, 1 = both high, 2 = B high, 3 = both low
        *c->phase_a = c->quad == 0 || c->quad == 1;
        *c->phase_b = c->quad == 1 || c->quad == 2;
        *c->phase_z = c->quad == 0 && c->pulse == 0;
    }
}

int rtapi_app_main(void) {
    if (num_chan < 0 || num_chan > SE_MAX_CHAN) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SIM_ENCODER: ERROR: invalid number of channels %d\n",
                        num_chan);
        return -EPERM;
    }
    bool named = names[0] != NULL && names[0][0] != '\0';
    int count = num_chan == 0 && !named ? 1 : num_chan;
    /* ".rawcounts": the longest suffix of a channel's pins */
    int n = halcomp_instance_names("sim_encoder", "sim-encoder", "num_chan", count, SE_MAX_CHAN,
                                   names, SE_MAX_CHAN, 10, cfg_names);
    if (n < 0)
        return n;
    cfg_nchan = n;
    halcomp_args_t args = {0};
    return HALCOMP_LOAD(&args);
}

void rtapi_app_exit(void) {
    hal_exit(comp_id);
}
