/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * conv.c - the conv_IN_OUT type converters (conv_bit_float, conv_float_s32,
 * conv_s32_u32, ...).  This one source is compiled once per pair with
 * -DCONV_IN=<k> -DCONV_OUT=<k> (k: 1 bit, 2 float, 3 s32, 4 u32, the
 * hal_type_t codes); see CMakeLists.txt.
 *
 * Names and behaviour are those of LinuxCNC 2.9 (module conv_in_out, pins
 * under conv-in-out.N): pins in (IN) and out (OUT); when the output type
 * cannot hold every input value also out-of-range (bit OUT) and the
 * parameter clamp (bit RW).  Floating point is used when either side is
 * float.
 *
 * Conversion rules, checked value by value against 2.9 (docs/conv.md):
 *  - clamp TRUE: an input above the output's maximum gives the maximum,
 *    below the minimum the minimum, both with out-of-range TRUE; otherwise
 *    out = in converted and out-of-range FALSE.  (2.9 uses 2147483647 as
 *    the clamp maximum of conv_float_u32; so do we.)
 *  - clamp FALSE: out = in converted as the C cast does on x86-64, and
 *    out-of-range becomes TRUE whenever out != in (compared with C's usual
 *    conversions) and then stays TRUE (2.9 never clears it in this mode).
 * The x86-64 results of out-of-range float casts (INT32_MIN for s32; the
 * low 32 bits of a 64-bit conversion for u32) are produced here without
 * undefined behaviour.
 */
#include <math.h>
#include <stdint.h>

#include "hm_simple.h"

#if !defined(CONV_IN) || !defined(CONV_OUT)
#error "compile with -DCONV_IN=<type code> -DCONV_OUT=<type code>"
#endif

#define K_BIT 1
#define K_FLOAT 2
#define K_S32 3
#define K_U32 4

#if CONV_IN == K_BIT
typedef hal_bit_t in_t;
typedef bool in_val_t;
#define IN_TYPE HAL_BIT
#elif CONV_IN == K_FLOAT
typedef hal_float_t in_t;
typedef double in_val_t;
#define IN_TYPE HAL_FLOAT
#elif CONV_IN == K_S32
typedef hal_s32_t in_t;
typedef rtapi_s32 in_val_t;
#define IN_TYPE HAL_S32
#elif CONV_IN == K_U32
typedef hal_u32_t in_t;
typedef rtapi_u32 in_val_t;
#define IN_TYPE HAL_U32
#endif

#if CONV_OUT == K_BIT
typedef hal_bit_t out_t;
typedef bool out_val_t;
#define OUT_TYPE HAL_BIT
#elif CONV_OUT == K_FLOAT
typedef hal_float_t out_t;
typedef double out_val_t;
#define OUT_TYPE HAL_FLOAT
#elif CONV_OUT == K_S32
typedef hal_s32_t out_t;
typedef rtapi_s32 out_val_t;
#define OUT_TYPE HAL_S32
#elif CONV_OUT == K_U32
typedef hal_u32_t out_t;
typedef rtapi_u32 out_val_t;
#define OUT_TYPE HAL_U32
#endif

/* Range limits of the output where the input can exceed them. */
#if CONV_IN == K_FLOAT && CONV_OUT == K_S32
#define HAS_MIN 1
#define OUT_MIN INT32_MIN
#define HAS_MAX 1
#define OUT_MAX INT32_MAX
#elif CONV_IN == K_FLOAT && CONV_OUT == K_U32
#define HAS_MIN 1
#define OUT_MIN 0
#define HAS_MAX 1
#define OUT_MAX INT32_MAX /* sic: LinuxCNC 2.9's value */
#elif CONV_IN == K_S32 && CONV_OUT == K_BIT
#define HAS_MIN 1
#define OUT_MIN 0
#define HAS_MAX 1
#define OUT_MAX 1
#elif CONV_IN == K_S32 && CONV_OUT == K_U32
#define HAS_MIN 1
#define OUT_MIN 0
#define HAS_MAX 0
#elif CONV_IN == K_U32 && CONV_OUT == K_BIT
#define HAS_MIN 0
#define HAS_MAX 1
#define OUT_MAX 1
#elif CONV_IN == K_U32 && CONV_OUT == K_S32
#define HAS_MIN 0
#define HAS_MAX 1
#define OUT_MAX INT32_MAX
#else
#define HAS_MIN 0
#define HAS_MAX 0
#endif

#define HAS_RANGE (HAS_MIN || HAS_MAX)
#define USES_FP (CONV_IN == K_FLOAT || CONV_OUT == K_FLOAT)

/* in -> out as gcc's cast does on x86-64, defined for every input. */
static out_val_t cast(in_val_t in)
{
#if CONV_IN == K_FLOAT && CONV_OUT == K_S32
    /* cvttsd2si: NaN and values whose truncation does not fit -> INT32_MIN */
    if (isnan(in) || in >= 2147483648.0 || in <= -2147483649.0)
        return INT32_MIN;
    return (rtapi_s32)in;
#elif CONV_IN == K_FLOAT && CONV_OUT == K_U32
    /* converted through a 64-bit cvttsd2si, then truncated to 32 bits */
    if (isnan(in) || in >= 9223372036854775808.0 || in < -9223372036854775808.0)
        return 0;
    return (rtapi_u32)(rtapi_s64)in;
#elif CONV_OUT == K_BIT
    return in != 0;
#elif CONV_IN == K_U32 && CONV_OUT == K_S32
    return (rtapi_s32)(in > INT32_MAX ? (rtapi_s64)in - 4294967296LL : (rtapi_s64)in);
#else
    return (out_val_t)in;
#endif
}

typedef struct {
    in_t *in;
    out_t *out;
#if HAS_RANGE
    hal_bit_t *out_of_range;
    hal_bit_t clamp;
#endif
} conv_t;

static void conv_update(void *arg, long period)
{
    conv_t *p = arg;
    in_val_t in = *p->in;
    (void)period;
#if HAS_RANGE
    if (p->clamp) {
#if HAS_MAX
        if (in > OUT_MAX) {
            *p->out = OUT_MAX;
            *p->out_of_range = 1;
            return;
        }
#endif
#if HAS_MIN
        if (in < OUT_MIN) {
            *p->out = OUT_MIN;
            *p->out_of_range = 1;
            return;
        }
#endif
        *p->out = cast(in);
        *p->out_of_range = 0;
        return;
    }
    {
        out_val_t out = cast(in);
        *p->out = out;
#if CONV_IN == K_FLOAT
        if ((double)out != in)
#elif CONV_OUT == K_BIT
        if ((rtapi_s64)out != (rtapi_s64)in)
#else
        /* C's usual conversions compare s32 and u32 as unsigned */
        if ((rtapi_u32)out != (rtapi_u32)in)
#endif
            *p->out_of_range = 1;
    }
#else
    *p->out = cast(in);
#endif
}

static const hm_item_t conv_pins[] = {
    HM_PIN(conv_t, in, IN_TYPE, HAL_IN, 0),
    HM_PIN(conv_t, out, OUT_TYPE, HAL_OUT, 0),
#if HAS_RANGE
    HM_PIN_N(conv_t, out_of_range, "out-of-range", HAL_BIT, HAL_OUT, 0),
#endif
};

#if HAS_RANGE
static const hm_item_t conv_params[] = {
    HM_PIN(conv_t, clamp, HAL_BIT, HAL_RW, 0),
};
#endif

static const hm_comp_desc_t conv_desc = {
    .modname = CONV_MODNAME,
    .prefix = CONV_PREFIX,
    .inst_size = sizeof(conv_t),
    .pins = conv_pins,
    .npins = HM_COUNT(conv_pins),
#if HAS_RANGE
    .params = conv_params,
    .nparams = HM_COUNT(conv_params),
#endif
    .funct = conv_update,
    .uses_fp = USES_FP,
};

HM_SIMPLE_COMPONENT(conv_desc, "Convert a value from one HAL type to another");
