/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_string.h - string functions for components: the C library's
 * (strlen, strcmp, memcpy, ...) and LinuxCNC's bounded copies.
 */
#ifndef HM_RTAPI_STRING_H
#define HM_RTAPI_STRING_H

#include <errno.h>
#include <stddef.h>
#include <string.h>

/* Names inside these functions carry an rtapi_ prefix: a .comp file may
 * include this header after its pin macros (a pin named `size`, say). */

/* Copy src into dst (size bytes), always NUL-terminated when size > 0.
 * Returns strlen(src), so a result >= size means it was truncated. */
static inline size_t rtapi_strlcpy(char *rtapi_dst_, const char *rtapi_src_, size_t rtapi_size_)
{
    size_t rtapi_len_ = strlen(rtapi_src_);
    if (rtapi_size_ > 0) {
        size_t rtapi_k_ = rtapi_len_ < rtapi_size_ - 1 ? rtapi_len_ : rtapi_size_ - 1;
        memcpy(rtapi_dst_, rtapi_src_, rtapi_k_);
        rtapi_dst_[rtapi_k_] = '\0';
    }
    return rtapi_len_;
}

/* Append src to the string in dst (size bytes in all), NUL-terminated.
 * Returns the length the whole string would have had. */
static inline size_t rtapi_strlcat(char *rtapi_dst_, const char *rtapi_src_, size_t rtapi_size_)
{
    size_t rtapi_have_ = strnlen(rtapi_dst_, rtapi_size_);
    if (rtapi_have_ == rtapi_size_)
        return rtapi_size_ + strlen(rtapi_src_);
    return rtapi_have_ +
           rtapi_strlcpy(rtapi_dst_ + rtapi_have_, rtapi_src_, rtapi_size_ - rtapi_have_);
}

/* Copy that reports truncation: 0, or -E2BIG (nothing is lost silently). */
static inline int rtapi_strxcpy_(char *rtapi_dst_, const char *rtapi_src_, size_t rtapi_size_)
{
    return rtapi_strlcpy(rtapi_dst_, rtapi_src_, rtapi_size_) >= rtapi_size_ ? -E2BIG : 0;
}
#define rtapi_strxcpy(dst, src) rtapi_strxcpy_((dst), (src), sizeof(dst))
#define rtapi_strxcat(dst, src) \
    (rtapi_strlcat((dst), (src), sizeof(dst)) >= sizeof(dst) ? -E2BIG : 0)

#endif /* HM_RTAPI_STRING_H */
