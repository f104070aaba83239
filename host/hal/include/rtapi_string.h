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

/* Copy src into dst (size bytes), always NUL-terminated when size > 0.
 * Returns strlen(src), so a result >= size means it was truncated. */
static inline size_t rtapi_strlcpy(char *dst, const char *src, size_t size)
{
    size_t len = strlen(src);
    if (size > 0) {
        size_t n = len < size - 1 ? len : size - 1;
        memcpy(dst, src, n);
        dst[n] = '\0';
    }
    return len;
}

/* Append src to the string in dst (size bytes in all), NUL-terminated.
 * Returns the length the whole string would have had. */
static inline size_t rtapi_strlcat(char *dst, const char *src, size_t size)
{
    size_t have = strnlen(dst, size);
    if (have == size)
        return size + strlen(src);
    return have + rtapi_strlcpy(dst + have, src, size - have);
}

/* Copy that reports truncation: 0, or -E2BIG (nothing is lost silently). */
static inline int rtapi_strxcpy_(char *dst, const char *src, size_t size)
{
    return rtapi_strlcpy(dst, src, size) >= size ? -E2BIG : 0;
}
#define rtapi_strxcpy(dst, src) rtapi_strxcpy_((dst), (src), sizeof(dst))
#define rtapi_strxcat(dst, src) \
    (rtapi_strlcat((dst), (src), sizeof(dst)) >= sizeof(dst) ? -E2BIG : 0)

#endif /* HM_RTAPI_STRING_H */
