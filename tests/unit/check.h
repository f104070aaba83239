/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * check.h - the project's minimal C unit-test harness.
 *
 *   static void test_something(void) { CHECK(x == 1); CHECK_EQ_INT(a, b); }
 *   int main(void) { RUN(test_something); return check_summary(); }
 *
 * Each test binary is one ctest test; a failed CHECK prints file:line and
 * the expression, the binary exits non-zero.
 */
#ifndef HM_CHECK_H
#define HM_CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int check_failures_;
static int check_count_;
static const char *check_current_ = "";

#define CHECK(expr)                                                              \
    do {                                                                         \
        check_count_++;                                                          \
        if (!(expr)) {                                                           \
            check_failures_++;                                                   \
            fprintf(stderr, "%s:%d: %s: CHECK(%s) failed\n", __FILE__, __LINE__, \
                    check_current_, #expr);                                      \
        }                                                                        \
    } while (0)

#define CHECK_EQ_INT(a, b)                                                          \
    do {                                                                            \
        long long a_ = (long long)(a), b_ = (long long)(b);                         \
        check_count_++;                                                             \
        if (a_ != b_) {                                                             \
            check_failures_++;                                                      \
            fprintf(stderr, "%s:%d: %s: %s == %s failed: %lld != %lld\n", __FILE__, \
                    __LINE__, check_current_, #a, #b, a_, b_);                      \
        }                                                                           \
    } while (0)

#define CHECK_EQ_STR(a, b)                                                         \
    do {                                                                           \
        const char *a_ = (a), *b_ = (b);                                           \
        check_count_++;                                                            \
        if (a_ == NULL || b_ == NULL || strcmp(a_, b_) != 0) {                     \
            check_failures_++;                                                     \
            fprintf(stderr, "%s:%d: %s: %s == %s failed:\n  got:  \"%s\"\n  want: \"%s\"\n", \
                    __FILE__, __LINE__, check_current_, #a, #b, a_ ? a_ : "(null)", \
                    b_ ? b_ : "(null)");                                           \
        }                                                                          \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                      \
    do {                                                                           \
        double a_ = (a), b_ = (b);                                                 \
        check_count_++;                                                            \
        if (!(fabs(a_ - b_) <= (tol))) {                                           \
            check_failures_++;                                                     \
            fprintf(stderr, "%s:%d: %s: |%s - %s| <= %g failed: %.17g vs %.17g\n", \
                    __FILE__, __LINE__, check_current_, #a, #b, (double)(tol), a_, b_); \
        }                                                                          \
    } while (0)

#define RUN(fn)                  \
    do {                         \
        check_current_ = #fn;    \
        fn();                    \
    } while (0)

static inline int check_summary(void)
{
    fprintf(stderr, "%d checks, %d failed\n", check_count_, check_failures_);
    return check_failures_ ? 1 : 0;
}

#endif /* HM_CHECK_H */
