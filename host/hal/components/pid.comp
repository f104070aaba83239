// SPDX-License-Identifier: GPL-2.0-or-later
//
// pid: proportional/integral/derivative loop with feed-forward and relay
// auto-tuning, pin for pin LinuxCNC 2.9's pid (docs/pid.md).  The
// arithmetic is math/pid_math.h; this file is the HAL side: the num_chan= /
// names= / debug= load options, the pins, and "is command-deriv /
// feedback-deriv connected to a signal?" (an unlinked pin points at its own
// dummy storage, whose address is noted right after loading).
component pid "Proportional/integral/derivative controller with automatic tuning support";
pin in float command "The desired (commanded) value";
pin in float command_deriv "Derivative of command; estimated numerically when not connected";
pin in float feedback "The actual value, from a sensor such as an encoder";
pin in float feedback_deriv "Derivative of feedback; estimated numerically when not connected";
pin in bit error_previous_target = TRUE "Error from the previous period's command";
pin out float error "command - feedback";
pin out float output "The output of the loop";
pin in bit enable "FALSE: output 0 and the integrator reset";
pin in bit index_enable "On its falling edge the derivative estimates are held";
pin in float Pgain = 1.0 "Proportional gain";
pin in float Igain "Integral gain";
pin in float Dgain "Derivative gain";
pin in float bias "Constant added to the output";
pin in float FF0 "Zeroth order feed-forward gain";
pin in float FF1 "First order feed-forward gain";
pin in float FF2 "Second order feed-forward gain";
pin in float FF3 "Third order feed-forward gain";
pin in float deadband "Errors smaller than this are ignored";
pin in float maxerror "Limit on the error (0: none)";
pin in float maxerrorI "Limit on the error integral (0: none)";
pin in float maxerrorD "Limit on the error derivative (0: none)";
pin in float maxcmdD "Limit on the command derivative (0: none)";
pin in float maxcmdDD "Limit on the command 2nd derivative (0: none)";
pin in float maxcmdDDD "Limit on the command 3rd derivative (0: none)";
pin in float maxoutput "Limit on the output (0: none)";
pin out bit saturated "TRUE while the output is at +-maxoutput";
pin out float saturated_s "Seconds the output has been saturated";
pin out s32 saturated_count "Periods the output has been saturated";
pin out float errorI if debug "Integral of the error";
pin out float errorD if debug "Derivative of the error";
pin out float commandD if debug "Derivative of the command";
pin out float commandDD if debug "2nd derivative of the command";
pin out float commandDDD if debug "3rd derivative of the command";
pin in bit tune_mode "TRUE: auto-tune mode, the loop does not run";
pin io bit tune_start "Set to start auto-tuning; cleared when it ends";
pin io u32 tune_type = 0 "0: tune Pgain/Igain/Dgain, 1: Pgain/Igain/FF1";
pin io u32 tune_cycles = 50 "Half cycles of the relay oscillation measured";
pin io float tune_effort = 0.5 "Relay output amplitude around bias";
pin out float ultimate_gain if debug "Measured ultimate gain";
pin out float ultimate_period if debug "Measured ultimate period (s)";
variable pid_state_t st;
variable pid_tune_t tune;
variable void *cmd_deriv_unlinked;
variable void *fb_deriv_unlinked;
function do_pid_calcs;
option rtapi_app no;
option default_count 1;
include "math/pid_math.h";
license "GPL";
;;
#define PID_MAX_CHAN 16

static int num_chan;
RTAPI_MP_INT(num_chan, "number of pid loops (default 1 as the seed documents, at most 16)");
static int debug;
RTAPI_MP_INT(debug, "1: export the internal values (errorI, commandD, ...)");
static char *names[PID_MAX_CHAN];
RTAPI_MP_ARRAY_STRING(names, PID_MAX_CHAN, "names of the pid loops");

/* The tuner writes the gains it found into these IN pins, as 2.9 does. */
#undef Pgain
#define Pgain (*__comp_inst->Pgain)
#undef Igain
#define Igain (*__comp_inst->Igain)
#undef Dgain
#define Dgain (*__comp_inst->Dgain)
#undef FF1
#define FF1 (*__comp_inst->FF1)
/* The -deriv pins are used through their pointers (see rtapi_app_main). */
#undef command_deriv
#undef feedback_deriv

FUNCTION(do_pid_calcs) {
    pid_inputs_t in = {
        .cmd = command,
        .fb = feedback,
        .cmd_d_in = *__comp_inst->command_deriv,
        .fb_d_in = *__comp_inst->feedback_deriv,
        .cmd_d_given = (void *)__comp_inst->command_deriv != cmd_deriv_unlinked,
        .fb_d_given = (void *)__comp_inst->feedback_deriv != fb_deriv_unlinked,
        .on = enable,
        .index = index_enable,
        .prev_target = error_previous_target,
    };
    pid_gains_t g = {
        .kp = Pgain, .ki = Igain, .kd = Dgain, .offset = bias,
        .ff0 = FF0, .ff1 = FF1, .ff2 = FF2, .ff3 = FF3,
        .db = deadband, .lim_err = maxerror, .lim_err_i = maxerrorI,
        .lim_err_d = maxerrorD, .lim_cmd_d = maxcmdD, .lim_cmd_dd = maxcmdDD,
        .lim_cmd_ddd = maxcmdDDD, .lim_out = maxoutput,
    };
    tune.active = tune_mode;
    tune.start = tune_start;
    tune.type = tune_type;
    tune.cycles = tune_cycles;
    tune.effort = tune_effort;

    pid_step(&st, &tune, &in, &g, period);

    output = st.out;
    error = st.err;
    saturated = st.sat;
    saturated_s = st.sat_s;
    saturated_count = st.sat_count;
    tune_start = tune.start;
    if (tune.gains_found) {
        Pgain = g.kp;
        Igain = g.ki;
        Dgain = g.kd;
        FF1 = g.ff1;
    }
    if (debug) {
        errorI = st.err_i;
        errorD = st.err_d;
        commandD = st.cmd_d;
        commandDD = st.cmd_dd;
        commandDDD = st.cmd_ddd;
        ultimate_gain = tune.ku;
        ultimate_period = tune.pu;
    }
}

int rtapi_app_main(void) {
    if (num_chan < 0 || num_chan > PID_MAX_CHAN) {
        rtapi_print_msg(RTAPI_MSG_ERR, "PID: ERROR: invalid number of channels: %d\n", num_chan);
        return -EINVAL;
    }
    halcomp_args_t args = {
        .count = num_chan,
        .names = names,
        .count_name = "num_chan",
        .max_count = PID_MAX_CHAN,
        .max_names = PID_MAX_CHAN,
    };
    int r = HALCOMP_LOAD(&args);
    if (r != 0)
        return r;
    /* Nothing is linked yet: each -deriv pin points at its own dummy. */
    struct __comp_state *__comp_inst;
    FOR_ALL_INSTS() {
        cmd_deriv_unlinked = (void *)__comp_inst->command_deriv;
        fb_deriv_unlinked = (void *)__comp_inst->feedback_deriv;
    }
    return 0;
}

void rtapi_app_exit(void) {
    hal_exit(comp_id);
}
