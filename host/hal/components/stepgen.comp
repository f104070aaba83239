// SPDX-License-Identifier: GPL-2.0-or-later
//
// stepgen: software step pulse generation, LinuxCNC 2.9's stepgen (step
// types 0-15, position and velocity mode, its pins, parameters, functions
// and load options; docs/stepgen.md).  The step generator itself is
// math/stepgen_math.h.  Which pins and parameters a channel has depends on
// its step type, so they are made here in EXTRA_SETUP rather than declared;
// every channel is served by the three module-wide functions, as in 2.9.
component stepgen "Software step pulse generation";
function make_pulses nofp "Generates the step pulses (run it in a fast thread)";
function update_freq "Turns the position or velocity commands into step frequencies";
function capture_position "Publishes counts and position-fb";
variable int nchan;
variable sg_timebase_t tb;
variable sg_chan_t ch[16];
variable hal_bit_t *en[16];
variable hal_float_t *cmd[16];
variable hal_s32_t *cnt[16];
variable hal_float_t *fb[16];
variable hal_bit_t *outpin[80];
variable int nout[16];
option singleton;
option rtapi_app no;
option extra_setup;
include "math/stepgen_math.h";
license "GPL";
;;
#define SG_MAX_CHAN 16

static int step_type[SG_MAX_CHAN] = {-1, -1, -1, -1, -1, -1, -1, -1,
                                     -1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(step_type, SG_MAX_CHAN, "stepping types for up to 16 channels");
static char *ctrl_type[SG_MAX_CHAN];
RTAPI_MP_ARRAY_STRING(ctrl_type, SG_MAX_CHAN, "control type (p or v) for up to 16 channels");
static int user_step_type[SG_USER_STEPS] = {-1, -1, -1, -1, -1, -1, -1, -1, -1,
                                            -1, -1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(user_step_type, SG_USER_STEPS, "output states of step type 15");

/* What the load options ask for, checked before HAL is touched. */
static int cfg_nchan, cfg_user_len;
static bool cfg_pos[SG_MAX_CHAN];

static void report_too_fast(int chan, int want, int limit)
{
    rtapi_print_msg(RTAPI_MSG_ERR,
                    "STEPGEN: Channel %d: The requested maximum velocity of %d steps/sec is too "
                    "high.\n",
                    chan, want);
    rtapi_print_msg(RTAPI_MSG_ERR, "STEPGEN: The maximum possible frequency is %d steps/second\n",
                    limit);
}

static int check_args(void)
{
    int n = 0;
    while (n < SG_MAX_CHAN && step_type[n] >= 0) {
        if (step_type[n] > SG_USER_TYPE) {
            rtapi_print_msg(RTAPI_MSG_ERR, "STEPGEN: ERROR: bad stepping type '%i', axis %i\n",
                            step_type[n], n);
            return -EINVAL;
        }
        n++;
    }
    if (n == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "STEPGEN: ERROR: no channels configured\n");
        return -EINVAL;
    }
    for (int i = 0; i < n; i++) {
        /* the first character counts: "pos" and "velocity" work too (2.9) */
        char t = ctrl_type[i] ? ctrl_type[i][0] : '\0';
        if (t == '\0' || t == 'p' || t == 'P') {
            cfg_pos[i] = true;
        } else if (t == 'v' || t == 'V') {
            cfg_pos[i] = false;
        } else {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "STEPGEN: ERROR: bad control type '%c' for axis %i (must be 'p' or "
                            "'v')\n",
                            t, i);
            return -EINVAL;
        }
    }
    int len = 0;
    while (len < SG_USER_STEPS && user_step_type[len] != -1)
        len++;
    if (sg_user_phases(user_step_type, len) < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "STEPGEN: ERROR: bad user step type uses more than 5 phases\n");
        return -EINVAL;
    }
    cfg_nchan = n;
    cfg_user_len = len;
    return 0;
}

static int make_outputs(int k, hal_bit_t **pins, int type)
{
    static const char *const names01[2][2] = {{"step", "dir"}, {"up", "down"}};
    int n;
    if (type <= 1)
        n = 2;
    else if (type == SG_USER_TYPE)
        n = sg_user_phases(user_step_type, cfg_user_len);
    else
        n = sg_patterns[type].phases;
    for (int i = 0; i < n; i++) {
        int r = type <= 1 ? hal_pin_bit_newf(HAL_OUT, &pins[i], comp_id, "stepgen.%d.%s", k,
                                             names01[type][i])
                          : hal_pin_bit_newf(HAL_OUT, &pins[i], comp_id, "stepgen.%d.phase-%c",
                                             k, 'A' + i);
        if (r != 0)
            return r;
    }
    return n;
}

static int make_channel(struct __comp_state *__comp_inst, int k)
{
    sg_chan_t *c = &ch[k];
    int type = step_type[k];
    int r;
    sg_chan_init(c, type, cfg_pos[k], user_step_type, cfg_user_len);
    if ((r = hal_pin_s32_newf(HAL_OUT, &cnt[k], comp_id, "stepgen.%d.counts", k)) ||
        (r = hal_pin_float_newf(HAL_OUT, &fb[k], comp_id, "stepgen.%d.position-fb", k)) ||
        (r = hal_pin_bit_newf(HAL_IN, &en[k], comp_id, "stepgen.%d.enable", k)) ||
        (r = hal_pin_float_newf(HAL_IN, &cmd[k], comp_id, "stepgen.%d.%s", k,
                                c->pos_mode ? "position-cmd" : "velocity-cmd")))
        return r;
    r = make_outputs(k, &outpin[k * SG_MAX_PHASES], type);
    if (r < 0)
        return r;
    nout[k] = r;
    if ((r = hal_param_float_newf(HAL_RO, &c->freq, comp_id, "stepgen.%d.frequency", k)) ||
        (r = hal_param_float_newf(HAL_RW, &c->maxaccel, comp_id, "stepgen.%d.maxaccel", k)) ||
        (r = hal_param_float_newf(HAL_RW, &c->maxvel, comp_id, "stepgen.%d.maxvel", k)) ||
        (r = hal_param_float_newf(HAL_RW, &c->scale, comp_id, "stepgen.%d.position-scale", k)) ||
        (r = hal_param_s32_newf(HAL_RO, &c->rawcount, comp_id, "stepgen.%d.rawcounts", k)) ||
        (r = hal_param_u32_newf(HAL_RW, &c->steplen, comp_id, "stepgen.%d.steplen", k)))
        return r;
    if (type <= 1 &&
        (r = hal_param_u32_newf(HAL_RW, &c->stepspace, comp_id, "stepgen.%d.stepspace", k)))
        return r;
    if (type == 0 &&
        ((r = hal_param_u32_newf(HAL_RW, &c->dirsetup, comp_id, "stepgen.%d.dirsetup", k)) ||
         (r = hal_param_u32_newf(HAL_RW, &c->dirhold, comp_id, "stepgen.%d.dirhold", k))))
        return r;
    if (type >= 1 &&
        (r = hal_param_u32_newf(HAL_RW, &c->dirdelay, comp_id, "stepgen.%d.dirdelay", k)))
        return r;
    return 0;
}

EXTRA_SETUP() {
    sg_timebase_init(&tb);
    nchan = cfg_nchan;
    for (int k = 0; k < cfg_nchan; k++) {
        int r = make_channel(__comp_inst, k);
        if (r != 0)
            return r;
    }
    return 0;
}

FUNCTION(make_pulses) {
    tb.make_period = period;
    for (int k = 0; k < nchan; k++) {
        sg_chan_t *c = &ch[k];
        sg_make_pulses(c, *en[k], period);
        hal_bit_t **pins = &outpin[k * SG_MAX_PHASES];
        unsigned out = c->out;
        for (int i = 0; i < nout[k]; i++)
            *pins[i] = (out >> i) & 1u;
    }
}

FUNCTION(update_freq) {
    sg_timebase_update(&tb, period);
    for (int k = 0; k < nchan; k++)
        sg_update_freq(&ch[k], &tb, *en[k], *cmd[k], k, report_too_fast);
}

FUNCTION(capture_position) {
    for (int k = 0; k < nchan; k++) {
        int32_t counts;
        double pos;
        sg_capture(&ch[k], &counts, &pos);
        *cnt[k] = counts;
        *fb[k] = pos;
    }
}

int rtapi_app_main(void) {
    int r = check_args();
    if (r != 0)
        return r;
    halcomp_args_t args = {0};
    return HALCOMP_LOAD(&args);
}

void rtapi_app_exit(void) {
    hal_exit(comp_id);
}
