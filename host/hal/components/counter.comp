// SPDX-License-Identifier: GPL-2.0-or-later
// counter: counts rising edges of phase-A (a unidirectional spindle
// sensor), with index reset, on the canonical encoder interface; LinuxCNC
// 2.9's names and its num_chan= load option (docs/counter.md).  Deprecated
// there in favour of encoder's counter mode; kept for old configurations.
// Two functions for all channels: counter.update-counters (sample the
// inputs, fast thread) and counter.capture-position (outputs, servo thread).
component counter "Count input pulses (deprecated: use encoder in counter mode)";
pin in bit phase_A "Counted on each rising edge";
pin in bit phase_Z "Index: with index-enable TRUE a rising edge zeroes the count";
pin io bit index_enable "Set TRUE to zero the count at the next index edge; cleared then";
pin in bit reset "TRUE holds the count at 0";
pin out s32 counts "The count at the last capture-position";
pin out float position "counts / position-scale";
pin out float velocity "Change of position per second between captures";
pin io float position_scale = 1.0 "Counts per unit of position";
pin out s32 rawcounts "The count, updated by update-counters";
variable int last_a;
variable int last_z;
variable hal_s32_t last_counts;
option rtapi_app no;
license "GPL";
;;
#include <rtapi_math.h>

#define COUNTER_MAX_CHAN 8

static int num_chan = 1;
RTAPI_MP_INT(num_chan, "number of channels (1 to 8)");

static void update_counters(void *arg, long period) {
    struct __comp_state *__comp_inst;
    (void)arg;
    (void)period;
    FOR_ALL_INSTS() {
        int a = phase_A;
        int z = phase_Z;
        if (a && !last_a)
            rawcounts = (hal_s32_t)((uint32_t)rawcounts + 1u);
        /* zeroing the count is not a movement: the velocity reference is
         * zeroed with it */
        if (z && !last_z && index_enable) {
            rawcounts = 0;
            last_counts = 0;
            index_enable = 0;
        }
        if (reset) {
            rawcounts = 0;
            last_counts = 0;
        }
        last_a = a;
        last_z = z;
    }
}

static void capture_position(void *arg, long period) {
    struct __comp_state *__comp_inst;
    (void)arg;
    FOR_ALL_INSTS() {
        double scale = position_scale;
        if (fabs(scale) < 1e-20) /* no division by (almost) zero: count units */
            scale = 1.0;
        hal_s32_t c = rawcounts;
        counts = c;
        position = c / scale;
        velocity = (hal_s32_t)((uint32_t)c - (uint32_t)last_counts) / scale / (period * 1e-9);
        last_counts = c;
    }
}

int rtapi_app_main(void) {
    if (num_chan < 1 || num_chan > COUNTER_MAX_CHAN) {
        rtapi_print_msg(RTAPI_MSG_ERR, "COUNTER: ERROR: invalid num_chan: %d (1 to %d)\n",
                        num_chan, COUNTER_MAX_CHAN);
        return -EINVAL;
    }
    comp_id = hal_init("counter");
    if (comp_id < 0)
        return comp_id;
    int r = 0;
    for (int i = 0; i < num_chan && r == 0; i++) {
        char name[HAL_NAME_LEN + 1];
        rtapi_snprintf(name, sizeof(name), "counter.%d", i);
        r = export(name, i);
    }
    if (r == 0)
        r = hal_export_funct("counter.update-counters", update_counters, NULL, 0, 0, comp_id);
    if (r == 0)
        r = hal_export_funct("counter.capture-position", capture_position, NULL, 1, 0, comp_id);
    if (r != 0) {
        hal_exit(comp_id);
        return r;
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void) {
    hal_exit(comp_id);
}
