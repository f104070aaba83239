// SPDX-License-Identifier: GPL-2.0-or-later
// weighted_sum: groups of bits to integers (sum of the weights of the TRUE
// bits plus an offset), LinuxCNC 2.9's names and load option
// (docs/weighted_sum.md):
//   loadrt weighted_sum wsum_sizes=4,2     -> wsum.0 (4 bits), wsum.1 (2 bits)
// One function, process_wsums, updates every summer.  The per-bit pins are
// made in EXTRA_SETUP because each summer has its own number of bits.
component weighted_sum "Convert groups of bits to integers";
pin in bit hold "TRUE: sum keeps its value";
pin io s32 offset "Added to the weights of the TRUE inputs";
pin out s32 sum "offset plus the weights of the TRUE inputs";
variable int nbits;
variable hal_bit_t *bit_in[32];
variable hal_s32_t *bit_weight[32];
option rtapi_app no;
option extra_setup yes;
license "GPL";
;;
#define WSUM_MAX_GROUPS 8
#define WSUM_MAX_BITS 32

/* -1 marks the end of the list, as in LinuxCNC */
static int wsum_sizes[WSUM_MAX_GROUPS] = {-1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(wsum_sizes, WSUM_MAX_GROUPS, "number of input bits of each summer (1 to 32)");

EXTRA_SETUP() {
    nbits = wsum_sizes[extra_arg];
    for (int m = 0; m < nbits; m++) {
        int r = hal_pin_bit_newf(HAL_IN, &bit_in[m], comp_id, "%s.bit.%d.in", prefix, m);
        if (r < 0)
            return r;
        r = hal_pin_s32_newf(HAL_IO, &bit_weight[m], comp_id, "%s.bit.%d.weight", prefix, m);
        if (r < 0)
            return r;
        /* 2^m; bit 31 gets the s32 value of 2^31, -2147483648 */
        *bit_weight[m] = (hal_s32_t)(1u << m);
    }
    return 0;
}

static void process_wsums(void *arg, long period) {
    struct __comp_state *__comp_inst;
    (void)arg;
    (void)period;
    FOR_ALL_INSTS() {
        if (hold)
            continue;
        /* unsigned: the sum wraps around like the s32 it ends up in */
        uint32_t s = (uint32_t)offset;
        for (int m = 0; m < nbits; m++) {
            if (*bit_in[m])
                s += (uint32_t)*bit_weight[m];
        }
        sum = (hal_s32_t)s;
    }
}

static int count_groups(void) {
    int n = 0;
    while (n < WSUM_MAX_GROUPS && wsum_sizes[n] != -1) {
        if (wsum_sizes[n] < 1 || wsum_sizes[n] > WSUM_MAX_BITS) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "WEIGHTED_SUM: ERROR: Invalid number of bits '%d' for summer %d "
                            "(1 to %d)\n",
                            wsum_sizes[n], n, WSUM_MAX_BITS);
            return -EINVAL;
        }
        n++;
    }
    if (n == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "WEIGHTED_SUM: ERROR: no summers specified\n");
        return -EINVAL;
    }
    return n;
}

int rtapi_app_main(void) {
    int n = count_groups();
    if (n < 0)
        return n;
    comp_id = hal_init("weighted_sum");
    if (comp_id < 0)
        return comp_id;
    int r = 0;
    for (int i = 0; i < n && r == 0; i++) {
        char name[HAL_NAME_LEN + 1];
        rtapi_snprintf(name, sizeof(name), "wsum.%d", i);
        r = export(name, i);
    }
    if (r == 0)
        r = hal_export_funct("process_wsums", process_wsums, NULL, 1, 0, comp_id);
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
