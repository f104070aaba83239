// SPDX-License-Identifier: GPL-2.0-or-later
// watchdog: monitors 1 to 32 inputs for a heartbeat (a change within each
// input's timeout), LinuxCNC 2.9's names and its num_inputs= load option
// (docs/watchdog.md).  set-timeouts (floating point, servo thread) turns
// the timeouts into nanoseconds and re-arms on a rising enable-in; process
// (no floating point, fast thread) checks the inputs.
component watchdog "Monitor inputs for a heartbeat";
pin in bit enable_in = FALSE "TRUE: monitor; a rising edge re-arms after a timeout";
pin out bit ok_out = FALSE "TRUE while enabled and no input has timed out";
variable int ninputs;
variable hal_bit_t *input[32];
variable hal_float_t timeout[32];
variable long timeout_ns[32];
variable long left_ns[32];
variable int last_input[32];
variable int last_enable;
variable int fault;
function process nofp "Check the inputs for changes; clear ok-out on a timeout";
function set_timeouts "Convert the timeouts to ns; re-arm on a rising enable-in";
option singleton yes;
option extra_setup yes;
license "GPL";
;;
#define WATCHDOG_MAX_INPUTS 32

static int num_inputs = -1;
RTAPI_MP_INT(num_inputs, "number of inputs (1 to 32)");

EXTRA_SETUP() {
    if (num_inputs < 1) {
        rtapi_print_msg(RTAPI_MSG_ERR, "WATCHDOG: ERROR: must specify at least one input "
                                       "(num_inputs=1 to 32)\n");
        return -EINVAL;
    }
    if (num_inputs > WATCHDOG_MAX_INPUTS) {
        rtapi_print_msg(RTAPI_MSG_ERR, "WATCHDOG: ERROR: too many inputs requested (%d > %d)\n",
                        num_inputs, WATCHDOG_MAX_INPUTS);
        return -EINVAL;
    }
    ninputs = num_inputs;
    for (int i = 0; i < ninputs; i++) {
        int r = hal_pin_bit_newf(HAL_IN, &input[i], comp_id, "%s.input-%d", prefix, i);
        if (r < 0)
            return r;
        r = hal_param_float_newf(HAL_RW, &timeout[i], comp_id, "%s.timeout-%d", prefix, i);
        if (r < 0)
            return r;
    }
    return 0;
}

FUNCTION(set_timeouts) {
    for (int i = 0; i < ninputs; i++) {
        double t = timeout[i];
        if (!(t >= 0))
            t = 0; /* negative or nan: no time at all, as a timeout of 0 */
        else if (t > 1e9)
            t = 1e9; /* some 30 years; keeps the ns count in range */
        timeout_ns[i] = (long)(t * 1e9);
    }
    int en = enable_in;
    if (en && !last_enable) {
        fault = 0;
        for (int i = 0; i < ninputs; i++) {
            left_ns[i] = timeout_ns[i];
            last_input[i] = *input[i];
        }
    }
    last_enable = en;
}

FUNCTION(process) {
    if (!enable_in) {
        ok_out = 0;
        return;
    }
    for (int i = 0; i < ninputs; i++) {
        int v = *input[i];
        if (v != last_input[i]) {
            last_input[i] = v;
            left_ns[i] = timeout_ns[i];
        } else if (left_ns[i] >= 0) {
            left_ns[i] -= period;
            if (left_ns[i] < 0)
                fault = 1;
        }
    }
    ok_out = !fault;
}
