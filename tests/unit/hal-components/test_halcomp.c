/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of libhalcomp's count=/names= resolution (halcomp.h), against
 * the rules of docs/halcompile.md (LOADING).
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "halcomp.h"

static void test_instance_names(void)
{
    char(*out)[HAL_NAME_LEN + 1] = calloc(HALCOMP_MAX_COUNT, sizeof(*out));
    char *none[4] = {NULL, NULL, NULL, NULL};
    /* count=0 with no names: no instances here (halcomp_load applies
     * default_count before asking) */
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 0, 1000, none, 4, 15, out), 0);
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 1, 1000, none, 4, 15, out), 1);
    CHECK_EQ_STR(out[0], "and2.0");
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 3, 1000, none, 4, 15, out), 3);
    CHECK_EQ_STR(out[2], "and2.2");
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", -1, 1000, none, 4, 15, out),
                 -EINVAL);
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 1001, 1000, none, 4, 15, out),
                 -EINVAL);
    char *two[4] = {"a", "b", NULL, NULL};
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 0, 1000, two, 4, 15, out), 2);
    CHECK_EQ_STR(out[1], "b");
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 2, 1000, two, 4, 15, out),
                 -EINVAL);
    char *dup[4] = {"a", "a", NULL, NULL};
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 0, 1000, dup, 4, 15, out),
                 -EINVAL);
    char *gap[4] = {"a", "", "b", NULL};
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 0, 1000, gap, 4, 15, out),
                 -EINVAL);
    char *blank[4] = {"a b", NULL, NULL, NULL};
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 0, 1000, blank, 4, 15, out),
                 -EINVAL);
    /* count=10: "and2.9" + 15 fits the 47 characters, a long prefix does not */
    CHECK_EQ_INT(halcomp_instance_names("x", "a-prefix-of-thirty-characterss", "count", 11, 1000,
                                        none, 4, 15, out),
                 -EINVAL);
    CHECK_EQ_INT(halcomp_instance_names("x", "a-prefix-of-thirty-charact", "count", 11, 1000,
                                        none, 4, 15, out),
                 11);
    CHECK_EQ_STR(out[10], "a-prefix-of-thirty-charact.10");
    /* 32 + 15 = 47 fits, 33 + 15 does not */
    char n32[40], n33[40];
    memset(n32, 'x', 32);
    n32[32] = '\0';
    memset(n33, 'x', 33);
    n33[33] = '\0';
    char *ok[4] = {n32, NULL, NULL, NULL};
    char *bad[4] = {n33, NULL, NULL, NULL};
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 0, 1000, ok, 4, 15, out), 1);
    CHECK_EQ_INT(halcomp_instance_names("and2", "and2", "count", 0, 1000, bad, 4, 15, out),
                 -EINVAL);
    free(out);
}

int main(void)
{
    RUN(test_instance_names);
    return check_summary();
}
