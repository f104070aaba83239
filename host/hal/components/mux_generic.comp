// SPDX-License-Identifier: GPL-2.0-or-later
// mux_generic: multiplexers of any size (1 to 1024 inputs) and any pair of
// input/output types, LinuxCNC 2.9's names and its config= load option
// (docs/mux_generic.md):
//   loadrt mux_generic config=bb8,fu12  -> mux-gen.00: 8 bits -> bit,
//                                          mux-gen.01: 12 floats -> u32
// Each entry is two type letters (b bit, f float, s s32, u u32; input type
// first, either case; one letter: the same type in and out) and the number
// of inputs.  Every mux has its own
// function, floating point only when a float is involved; its pins and the
// function are made in EXTRA_SETUP because types and sizes differ per mux.
component mux_generic "Choose one of several input values, of any type";
pin in bit suppress_no_input "TRUE: a selection of 0 keeps the output (in-00 unused)";
pin in u32 debounce_us "A new selection is used once it has differed this long (us)";
pin in u32 sel_int "Selection (plus the value of the sel-bit pins)";
param r u32 elapsed "Time the selection has differed from the one in use, in us (debounce)";
param r u32 selected "The selection in use (past the last input: the last input is used)";
variable int size;
variable int nbits;
variable int in_type;
variable int out_type;
variable hal_data_u **inputs;
variable hal_bit_t **sel_bit;
variable hal_data_u *output;
variable long long stable_ns;
option rtapi_app no;
option extra_setup yes;
license "GPL";
;;
#include <rtapi_math.h>

#define MUXGEN_MAX 100
#define MUXGEN_MAX_SIZE 1024

static char *config[MUXGEN_MAX];
RTAPI_MP_ARRAY_STRING(config, MUXGEN_MAX, "mux types and sizes, e.g. bb8,fu12");

typedef struct {
    int itype;
    int otype;
    int n;
} muxgen_cfg_t;

static hal_type_t muxgen_type(char c) {
    switch (c) {
    case 'b': case 'B': return HAL_BIT;
    case 'f': case 'F': return HAL_FLOAT;
    case 's': case 'S': return HAL_S32;
    case 'u': case 'U': return HAL_U32;
    default: return (hal_type_t)-1;
    }
}

static const char *muxgen_type_name(int t) {
    return t == HAL_BIT ? "bit" : t == HAL_FLOAT ? "float" : t == HAL_S32 ? "s32" : "u32";
}

/* "bb8": input type, output type, size; "b8": the same type in and out */
static int muxgen_parse(int i, const char *s, muxgen_cfg_t *c) {
    int it = s[0] ? (int)muxgen_type(s[0]) : -1;
    int two = s[0] && s[1] && (s[1] < '0' || s[1] > '9');
    int ot = two ? (int)muxgen_type(s[1]) : it;
    if (it < 0 || ot < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "mux_generic: ERROR: config entry %d '%s': type letters first "
                        "(b, f, s or u: input type, then output type)\n", i, s);
        return -EINVAL;
    }
    const char *p = s + (two ? 2 : 1);
    if (*p < '0' || *p > '9') {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "mux_generic: ERROR: config entry %d '%s': no entry count given\n", i, s);
        return -EINVAL;
    }
    long n = 0;
    for (; *p >= '0' && *p <= '9'; p++) {
        n = n * 10 + (*p - '0');
        if (n > MUXGEN_MAX_SIZE)
            break;
    }
    if (*p != '\0' && (*p < '0' || *p > '9')) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "mux_generic: ERROR: config entry %d '%s': invalid character '%c'\n", i,
                        s, *p);
        return -EINVAL;
    }
    if (n < 2 || n > MUXGEN_MAX_SIZE) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "mux_generic: ERROR: config entry %d '%s': size out of range (2 to %d)\n",
                        i, s, MUXGEN_MAX_SIZE);
        return -EINVAL;
    }
    c->itype = it;
    c->otype = ot;
    c->n = (int)n;
    return 0;
}

static int muxgen_count(void) {
    int n = 0;
    while (n < MUXGEN_MAX && config[n] != NULL && config[n][0] != '\0')
        n++;
    if (n == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "mux_generic: ERROR: no mux given: config=TYPESIZE[,...], e.g. bb8,fu12\n");
        return -EINVAL;
    }
    for (int i = n; i < MUXGEN_MAX; i++) {
        if (config[i] != NULL && config[i][0] != '\0') {
            rtapi_print_msg(RTAPI_MSG_ERR, "mux_generic: ERROR: config entry %d is empty\n", n);
            return -EINVAL;
        }
    }
    for (int i = 0; i < n; i++) {
        muxgen_cfg_t c;
        int r = muxgen_parse(i, config[i], &c);
        if (r < 0)
            return r;
    }
    return n;
}

/* Conversions as LinuxCNC 2.9 does them: to an integer type the float is
 * truncated and limited to the type's range (s32: -2147483647 to
 * 2147483647; nan gives -2147483648 for s32 and 0 for u32), a float is
 * TRUE when its size exceeds 2e-7, s32 to u32 limits negatives to 0, u32
 * to s32 limits to 2147483647. */
static rtapi_s32 muxgen_f2s(double v) {
    if (v != v)
        return INT32_MIN;
    if (v > 2147483647.0)
        return 2147483647;
    if (v < -2147483647.0)
        return -2147483647;
    return (rtapi_s32)v;
}

static rtapi_u32 muxgen_f2u(double v) {
    if (!(v > 0.0))
        return 0; /* also nan */
    if (v > 4294967295.0)
        return 4294967295u;
    return (rtapi_u32)v;
}

static int muxgen_f2b(double v) {
    return v > 2e-7 || v < -2e-7;
}

static void muxgen_copy(int it, int ot, const hal_data_u *in, hal_data_u *out) {
    switch (it) {
    case HAL_BIT: {
        int b = in->b;
        if (ot == HAL_BIT) out->b = b;
        else if (ot == HAL_FLOAT) out->f = b;
        else if (ot == HAL_S32) out->s = b;
        else out->u = (hal_u32_t)b;
        break;
    }
    case HAL_FLOAT: {
        double f = in->f;
        if (ot == HAL_BIT) out->b = muxgen_f2b(f);
        else if (ot == HAL_FLOAT) out->f = f;
        else if (ot == HAL_S32) out->s = muxgen_f2s(f);
        else out->u = muxgen_f2u(f);
        break;
    }
    case HAL_S32: {
        rtapi_s32 s = in->s;
        if (ot == HAL_BIT) out->b = s != 0;
        else if (ot == HAL_FLOAT) out->f = s;
        else if (ot == HAL_S32) out->s = s;
        else out->u = s > 0 ? (hal_u32_t)s : 0u;
        break;
    }
    default: {
        rtapi_u32 u = in->u;
        if (ot == HAL_BIT) out->b = u != 0;
        else if (ot == HAL_FLOAT) out->f = u;
        else if (ot == HAL_S32) out->s = u > 2147483647u ? 2147483647 : (hal_s32_t)u;
        else out->u = u;
        break;
    }
    }
}

static void muxgen_update(void *arg, long period) {
    struct __comp_state *__comp_inst = arg;
    uint64_t sel = sel_int;
    for (int m = 0; m < nbits; m++) {
        if (*sel_bit[m])
            sel += 1ull << m;
    }
    if (suppress_no_input && sel == 0)
        return;
    if (sel > 0xffffffffu)
        sel = 0xffffffffu;
    /* Debounce as LinuxCNC 2.9 does it: a new selection is taken once it has
     * differed from the one in use for debounce-us (counted from the first
     * period it differed, and from 0 again whenever the selection returns
     * to the one in use).  While a new selection waits, the output is left
     * alone. */
    if (sel != selected) {
        if (stable_ns >= (long long)debounce_us * 1000) {
            selected = (hal_u32_t)sel;
            stable_ns = 0;
            elapsed = 0;
        } else {
            stable_ns += period;
            elapsed = (hal_u32_t)(stable_ns / 1000);
            return;
        }
    } else {
        stable_ns = 0;
        elapsed = 0;
    }
    /* past the last input: the last input */
    hal_u32_t k = selected < (hal_u32_t)size ? selected : (hal_u32_t)size - 1;
    muxgen_copy(in_type, out_type, inputs[k], output);
}

EXTRA_SETUP() {
    muxgen_cfg_t c;
    int r = muxgen_parse((int)extra_arg, config[extra_arg], &c);
    if (r < 0)
        return r;
    size = c.n;
    in_type = c.itype;
    out_type = c.otype;
    /* sel-bit pins: log2(size) of them when size is a power of two or one
     * more than a power of two, none otherwise (LinuxCNC 2.9) */
    nbits = 0;
    while ((2 << nbits) <= size)
        nbits++;
    if (size - (1 << nbits) > 1)
        nbits = 0;
    inputs = hal_malloc(size * (long)sizeof(*inputs));
    sel_bit = hal_malloc((nbits ? nbits : 1) * (long)sizeof(*sel_bit));
    if (inputs == NULL || sel_bit == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "mux_generic: ERROR: out of HAL memory for %s\n", prefix);
        return -ENOMEM;
    }
    const char *tn_in = muxgen_type_name(in_type);
    for (int i = 0; i < size && r == 0; i++)
        r = hal_pin_newf((hal_type_t)in_type, HAL_IN, (void **)&inputs[i], comp_id, "%s.in-%s-%02d",
                         prefix, tn_in, i);
    for (int m = 0; m < nbits && r == 0; m++)
        r = hal_pin_bit_newf(HAL_IN, &sel_bit[m], comp_id, "%s.sel-bit-%02d", prefix, m);
    if (r == 0)
        r = hal_pin_newf((hal_type_t)out_type, HAL_OUT, (void **)&output, comp_id, "%s.out-%s",
                         prefix, muxgen_type_name(out_type));
    if (r == 0)
        r = hal_export_functf(muxgen_update, __comp_inst,
                              in_type == HAL_FLOAT || out_type == HAL_FLOAT, 0, comp_id, "%s",
                              prefix);
    return r;
}

int rtapi_app_main(void) {
    int n = muxgen_count();
    if (n < 0)
        return n;
    comp_id = hal_init("mux_generic");
    if (comp_id < 0)
        return comp_id;
    int r = 0;
    for (int i = 0; i < n && r == 0; i++) {
        char name[HAL_NAME_LEN + 1];
        rtapi_snprintf(name, sizeof(name), "mux-gen.%02d", i);
        r = export(name, i);
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
