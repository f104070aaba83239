// SPDX-License-Identifier: GPL-2.0-or-later
// watchdog: monitors 1 to 32 inputs for a heartbeat (a change within each
// input's timeout), LinuxCNC 2.9's names, load option and behaviour
// (docs/watchdog.md).  set-timeouts (floating point, servo thread) turns
// the timeouts into nanoseconds and arms the watchdog on a rising enable-in
// when it is not armed (at start, or after a timeout); process (no floating
// point, fast thread) watches the inputs while enable-in is TRUE and the
// watchdog is armed.  enable-in FALSE pauses everything: ok-out keeps its
// value and the time left of each input stands still.
component watchdog "Monitor inputs for a heartbeat";
pin in bit enable_in = FALSE "TRUE: watch the inputs; a rising edge arms the watchdog when not armed";
pin out bit ok_out = FALSE "TRUE from arming until an input times out";
variable int ninputs;
variable hal_bit_t *input[32];
variable hal_float_t timeout[32];
variable long timeout_ns[32];
variable long left_ns[32];
variable int last_input[32];
variable int last_enable;
variable int ok;
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
    if (en && !last_enable && !ok) {
        /* (re-)arm: every input gets its full timeout again */
        for (int i = 0; i < ninputs; i++)
            left_ns[i] = timeout_ns[i];
        ok = 1;
        ok_out = 1;
    }
    last_enable = en;
}

FUNCTION(process) {
    /* Disabled or timed out: nothing is watched and nothing changes (not
     * even the input history), as in LinuxCNC 2.9. */
    if (!enable_in || !ok)
        return;
    for (int i = 0; i < ninputs; i++) {
        int v = *input[i];
        if (v != last_input[i]) {
            last_input[i] = v;
            left_ns[i] = timeout_ns[i];
        } else {
            left_ns[i] -= period;
            if (left_ns[i] < 0)
                ok = 0;
        }
    }
    ok_out = ok;
}
