/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_math64.h - 64-bit division helpers with the LinuxCNC names (the
 * kernel needed them; in userspace they are plain C division).
 */
#ifndef HM_RTAPI_MATH64_H
#define HM_RTAPI_MATH64_H

#include "rtapi.h"

/* Quotient of n / base; the remainder is stored in *rem. */
static inline rtapi_u64 rtapi_div_u64_rem(rtapi_u64 n, rtapi_u32 base, rtapi_u32 *rem)
{
    *rem = (rtapi_u32)(n % base);
    return n / base;
}

static inline rtapi_u64 rtapi_div_u64(rtapi_u64 n, rtapi_u32 base)
{
    return n / base;
}

static inline rtapi_s64 rtapi_div_s64(rtapi_s64 n, rtapi_s32 base)
{
    return n / base;
}

#endif /* HM_RTAPI_MATH64_H */
