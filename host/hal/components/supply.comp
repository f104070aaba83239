// SPDX-License-Identifier: GPL-2.0-or-later
// supply: output pins that copy their I/O pins d and value (obsolete since
// setp and sets can drive unconnected pins and signals; kept for old
// configurations), LinuxCNC 2.9's names and its num_chan= load option
// (docs/supply.md).
component supply "Set output pins from values given with setp (obsolete)";
pin out bit q "Copy of d";
pin out float variable "Copy of value";
pin io bit d "Source of q and _q";
pin io float value "Source of variable and _variable";
// supply.N._q and supply.N._variable: HAL names with an underscore, which
// the pin declarations cannot make (they turn '_' into '-'), so EXTRA_SETUP
// makes them.
variable hal_bit_t *not_q;
variable hal_float_t *neg_variable;
function update "Update the output pins of this channel";
option rtapi_app no;
option extra_setup yes;
license "GPL";
;;
#define SUPPLY_MAX_CHAN 8

static int num_chan = 1;
RTAPI_MP_INT(num_chan, "number of channels (1 to 8)");

EXTRA_SETUP() {
    int r = hal_pin_bit_newf(HAL_OUT, &not_q, comp_id, "%s._q", prefix);
    if (r < 0)
        return r;
    r = hal_pin_float_newf(HAL_OUT, &neg_variable, comp_id, "%s._variable", prefix);
    if (r < 0)
        return r;
    *not_q = 1; /* the inverse of d (FALSE) from the start */
    return 0;
}

FUNCTION(update) {
    int b = d;
    double v = value;
    q = b;
    *not_q = !b;
    variable = v;
    *neg_variable = -v;
}

int rtapi_app_main(void) {
    if (num_chan < 1 || num_chan > SUPPLY_MAX_CHAN) {
        rtapi_print_msg(RTAPI_MSG_ERR, "SUPPLY: ERROR: invalid num_chan: %d (1 to %d)\n",
                        num_chan, SUPPLY_MAX_CHAN);
        return -EINVAL;
    }
    halcomp_args_t args = {
        .count = num_chan,
        .count_name = "num_chan",
        .max_count = SUPPLY_MAX_CHAN,
    };
    return HALCOMP_LOAD(&args);
}

void rtapi_app_exit(void) {
    hal_exit(comp_id);
}
