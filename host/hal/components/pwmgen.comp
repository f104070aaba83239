// SPDX-License-Identifier: GPL-2.0-or-later
//
// pwmgen: software PWM/PDM generation, LinuxCNC 2.9's pwmgen (output_type=
// 0 pwm, 1 pwm+dir, 2 up/down for up to 8 channels, its pins and its two
// module-wide functions; docs/pwmgen.md).  The pulse maker is
// math/pwmgen_math.h.  Which output pins a channel has depends on its
// output type, so the pins are made here in EXTRA_SETUP.
component pwmgen "Software PWM/PDM generation";
function make_pulses nofp "Makes the pulses (run it in a fast thread)";
function update "Turns value into a duty cycle, checks the settings";
variable int nchan;
variable long make_period;
variable pwmgen_hot_t hot[8];
variable pwmgen_chan_t ch[8];
option singleton;
option rtapi_app no;
option extra_setup;
include "pwmgen_chan.h";
license "GPL";
;;
#define PWM_MAX_CHAN 8

static int output_type[PWM_MAX_CHAN] = {-1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(output_type, PWM_MAX_CHAN, "output types for up to 8 channels");

static int cfg_nchan;

#define PWM_PIN(kind, dir, field, suffix)                                               \
    if ((r = hal_pin_##kind##_newf(dir, &(field), comp_id, "pwmgen.%d." suffix, k)) != 0) \
        return r

static int make_channel(pwmgen_hot_t *h, pwmgen_chan_t *c, int k)
{
    int r;
    h->type = output_type[k];
    PWM_PIN(float, HAL_IN, c->value, "value");
    PWM_PIN(bit, HAL_IN, c->enable, "enable");
    PWM_PIN(float, HAL_IO, c->scale, "scale");
    PWM_PIN(float, HAL_IO, c->offset, "offset");
    PWM_PIN(bit, HAL_IO, c->dither, "dither-pwm");
    PWM_PIN(float, HAL_IO, c->freq, "pwm-freq");
    PWM_PIN(float, HAL_IO, c->min_dc, "min-dc");
    PWM_PIN(float, HAL_IO, c->max_dc, "max-dc");
    PWM_PIN(float, HAL_OUT, c->curr_dc, "curr-dc");
    if (h->type == 2) {
        PWM_PIN(bit, HAL_OUT, h->out_a, "up");
        PWM_PIN(bit, HAL_OUT, h->out_b, "down");
    } else {
        PWM_PIN(bit, HAL_OUT, h->out_a, "pwm");
        if (h->type == 1)
            PWM_PIN(bit, HAL_OUT, h->out_b, "dir");
    }
    *c->scale = 1.0;
    *c->max_dc = 1.0;
    pwm_init(&c->p, &h->q);
    return 0;
}

EXTRA_SETUP() {
    make_period = PWM_NO_PERIOD;
    nchan = cfg_nchan;
    for (int k = 0; k < cfg_nchan; k++) {
        int r = make_channel(&hot[k], &ch[k], k);
        if (r != 0)
            return r;
    }
    return 0;
}

FUNCTION(make_pulses) {
    make_period = period;
    for (int k = 0; k < nchan; k++) {
        pwmgen_hot_t *h = &hot[k];
        pwm_make_pulses(&h->q, period);
        bool out = h->q.out, dir = h->q.direction;
        if (h->type == 2) {
            *h->out_a = out & !dir;
            *h->out_b = out & dir;
        } else {
            *h->out_a = out;
        }
    }
}

FUNCTION(update) {
    for (int k = 0; k < nchan; k++) {
        pwmgen_hot_t *h = &hot[k];
        pwmgen_chan_t *c = &ch[k];
        pwm_settings_t s = {*c->freq, *c->max_dc, *c->min_dc, *c->scale};
        pwm_update(&c->p, &h->q, make_period, &s, *c->value, *c->offset, *c->enable, *c->dither,
                   h->type != 0);
        /* 2.9 writes corrected settings back to their pins (NaN stays NaN) */
        if (s.freq != *c->freq)
            *c->freq = s.freq;
        if (s.max_dc != *c->max_dc)
            *c->max_dc = s.max_dc;
        if (s.min_dc != *c->min_dc)
            *c->min_dc = s.min_dc;
        if (s.scale != *c->scale)
            *c->scale = s.scale;
        *c->curr_dc = c->p.curr_dc;
        if (h->type == 1)
            *h->out_b = h->q.direction;
    }
}

int rtapi_app_main(void) {
    int n = 0;
    while (n < PWM_MAX_CHAN && output_type[n] >= 0) {
        if (output_type[n] > 2) {
            rtapi_print_msg(RTAPI_MSG_ERR, "PWMGEN: ERROR: bad output type '%i', channel %i\n",
                            output_type[n], n);
            return -EINVAL;
        }
        n++;
    }
    if (n == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "PWMGEN: ERROR: no channels configured\n");
        return -EINVAL;
    }
    cfg_nchan = n;
    halcomp_args_t args = {0};
    return HALCOMP_LOAD(&args);
}

void rtapi_app_exit(void) {
    hal_exit(comp_id);
}
