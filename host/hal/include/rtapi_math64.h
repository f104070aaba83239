/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_math64.h - 64-bit division helpers with the LinuxCNC names (the
 * kernel needed them; in userspace they are plain C division).
 */
#ifndef HM_RTAPI_MATH64_H
#define HM_RTAPI_MATH64_H

#include "rtapi.h"

/* Names inside these functions carry an rtapi_ prefix: a .comp file may
 * include this header after its pin macros (a pin named `rem`, say). */

/* Quotient of n / base; the remainder is stored in *rem. */
static inline rtapi_u64 rtapi_div_u64_rem(rtapi_u64 rtapi_n_, rtapi_u32 rtapi_base_,
                                          rtapi_u32 *rtapi_rem_)
{
    *rtapi_rem_ = (rtapi_u32)(rtapi_n_ % rtapi_base_);
    return rtapi_n_ / rtapi_base_;
}

static inline rtapi_u64 rtapi_div_u64(rtapi_u64 rtapi_n_, rtapi_u32 rtapi_base_)
{
    return rtapi_n_ / rtapi_base_;
}

static inline rtapi_s64 rtapi_div_s64(rtapi_s64 rtapi_n_, rtapi_s32 rtapi_base_)
{
    return rtapi_n_ / rtapi_base_;
}

#endif /* HM_RTAPI_MATH64_H */
