// SPDX-License-Identifier: GPL-2.0-or-later
// debounce: groups of digital input filters, LinuxCNC 2.9's names and load
// option (docs/debounce.md):
//   loadrt debounce cfg=1,4,2   -> groups debounce.0 (1 filter), debounce.1
//                                  (4 filters), debounce.2 (2 filters)
//   loadrt debounce             -> one group of one filter (the seed's default)
// Every filter of a group shares the group's delay and function.  Each
// filter counts up (to delay) while its input is TRUE and down (to 0) while
// it is FALSE; a TRUE input with the count already at delay makes the
// output TRUE, a FALSE input with the count at 0 makes it FALSE.  So with
// delay 0 the output follows the input, and with delay N a change must last
// N + 1 periods to get through.  A negative delay is set to 1.  The filters are
// made in EXTRA_SETUP because each group has its own number of them.
component debounce "Filter noisy digital inputs";
param rw s32 delay = 5 "Filter delay of the group, in periods";
variable int nfilt;
variable hal_bit_t **fin;
variable hal_bit_t **fout;
variable int *fcount;
function _ nofp "Sample every input of the group and update the outputs";
option rtapi_app no;
option extra_setup yes;
license "GPL";
;;
#define DEBOUNCE_MAX_GROUPS 8
#define DEBOUNCE_MAX_FILTERS 1000

/* -1 marks the end of the list */
static int cfg[DEBOUNCE_MAX_GROUPS] = {-1, -1, -1, -1, -1, -1, -1, -1};
RTAPI_MP_ARRAY_INT(cfg, DEBOUNCE_MAX_GROUPS, "number of filters in each group");

EXTRA_SETUP() {
    nfilt = cfg[extra_arg];
    fin = hal_malloc(nfilt * (long)sizeof(*fin));
    fout = hal_malloc(nfilt * (long)sizeof(*fout));
    fcount = hal_malloc(nfilt * (long)sizeof(*fcount));
    if (fin == NULL || fout == NULL || fcount == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "DEBOUNCE: ERROR: out of HAL memory for group %s\n",
                        prefix);
        return -ENOMEM;
    }
    for (int f = 0; f < nfilt; f++) {
        fcount[f] = 0;
        int r = hal_pin_bit_newf(HAL_IN, &fin[f], comp_id, "%s.%d.in", prefix, f);
        if (r < 0)
            return r;
        r = hal_pin_bit_newf(HAL_OUT, &fout[f], comp_id, "%s.%d.out", prefix, f);
        if (r < 0)
            return r;
    }
    return 0;
}

FUNCTION(_) {
    if (delay < 0)
        delay = 1; /* as LinuxCNC 2.9 does, visibly */
    int d = delay;
    for (int f = 0; f < nfilt; f++) {
        int c = fcount[f];
        if (c > d)
            c = d;
        if (*fin[f]) {
            if (c < d)
                c++;
            else
                *fout[f] = 1;
        } else {
            if (c > 0)
                c--;
            else
                *fout[f] = 0;
        }
        fcount[f] = c;
    }
}

static int count_groups(void) {
    int n = 0;
    while (n < DEBOUNCE_MAX_GROUPS && cfg[n] != -1) {
        if (cfg[n] < 1 || cfg[n] > DEBOUNCE_MAX_FILTERS) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "DEBOUNCE: ERROR: bad group size '%d' for group %d (1 to %d)\n",
                            cfg[n], n, DEBOUNCE_MAX_FILTERS);
            return -EINVAL;
        }
        n++;
    }
    if (n == 0) {
        /* the seed's default, one group of one filter (LinuxCNC 2.9 refuses
         * to load without cfg=) */
        cfg[0] = 1;
        n = 1;
    }
    return n;
}

int rtapi_app_main(void) {
    int n = count_groups();
    if (n < 0)
        return n;
    comp_id = hal_init("debounce");
    if (comp_id < 0)
        return comp_id;
    int r = 0;
    for (int g = 0; g < n && r == 0; g++) {
        char name[HAL_NAME_LEN + 1];
        rtapi_snprintf(name, sizeof(name), "debounce.%d", g);
        r = export(name, g);
    }
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
