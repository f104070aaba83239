/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Unit tests of halcmd's line preprocessing and tokenizing; the expected
 * results follow what LinuxCNC 2.9's halcmd does with the same lines. */
#define _GNU_SOURCE
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "halcmd_parse.h"

static char *ini_fake(const char *section, const char *key, void *ctx)
{
    (void)ctx;
    if (strcmp(section, "AXIS_0") == 0 && strcmp(key, "SCALE") == 0)
        return strdup("32000");
    return NULL;
}

static int tok(const char *line, char out[][64], int max)
{
    char buf[1024], err[128];
    char *t[64];
    if (halcmd_preprocess(line, buf, sizeof(buf), ini_fake, NULL, err, sizeof(err)) != 0)
        return -1;
    int n = halcmd_tokenize(buf, t, max, err, sizeof(err));
    for (int i = 0; i < n; i++)
        snprintf(out[i], 64, "%s", t[i]);
    return n;
}

static void test_comments(void)
{
    char t[8][64];
    CHECK_EQ_INT(tok("# comment", t, 8), 0);
    CHECK_EQ_INT(tok("   # indented", t, 8), 0);
    /* '#' ends the line anywhere, even inside a word (as LinuxCNC) */
    CHECK_EQ_INT(tok("newsig a#b float # x", t, 8), 2);
    CHECK_EQ_STR(t[1], "a");
    CHECK_EQ_INT(tok("", t, 8), 0);
    CHECK_EQ_INT(tok("  \t ", t, 8), 0);
}

static void test_tokens(void)
{
    char t[8][64];
    CHECK_EQ_INT(tok("net  a\tb  ==> c", t, 8), 5);
    CHECK_EQ_STR(t[0], "net");
    CHECK_EQ_STR(t[3], "==>");
    CHECK_EQ_STR(t[4], "c");
    /* quotes group blanks and are kept */
    CHECK_EQ_INT(tok("newsig \"c d\" float", t, 8), 3);
    CHECK_EQ_STR(t[1], "\"c d\"");
    CHECK_EQ_INT(tok("a b c d e f g h i", t, 8), -1); /* too many for max */
    CHECK_EQ_INT(tok("print \"unterminated", t, 8), -1);
}

static void test_substitution(void)
{
    char t[8][64];
    setenv("HM_TEST_VAR", "sig1", 1);
    CHECK_EQ_INT(tok("newsig $HM_TEST_VAR float", t, 8), 3);
    CHECK_EQ_STR(t[1], "sig1");
    CHECK_EQ_INT(tok("newsig x$(HM_TEST_VAR)y float", t, 8), 3);
    CHECK_EQ_STR(t[1], "xsig1y");
    CHECK_EQ_INT(tok("setp a [AXIS_0]SCALE", t, 8), 3);
    CHECK_EQ_STR(t[2], "32000");
    char buf[256], err[128];
    CHECK(halcmd_preprocess("setp a [AXIS_9]SCALE", buf, sizeof(buf), ini_fake, NULL, err,
                            sizeof(err)) == -1);
    CHECK_EQ_STR(err, "Ini variable '[AXIS_9]SCALE' not found.");
    unsetenv("HM_TEST_NOPE");
    CHECK(halcmd_preprocess("setp a $HM_TEST_NOPE", buf, sizeof(buf), NULL, NULL, err,
                            sizeof(err)) == -1);
    CHECK_EQ_STR(err, "Environment variable 'HM_TEST_NOPE' not set");
    CHECK(halcmd_preprocess("setp a $(HM_TEST_VAR", buf, sizeof(buf), NULL, NULL, err,
                            sizeof(err)) == -1);
    /* a lone $ and [] without key stay as they are */
    CHECK(halcmd_preprocess("echo $ [x] [", buf, sizeof(buf), NULL, NULL, err, sizeof(err)) == 0);
    CHECK_EQ_STR(buf, "echo $ [x] [");
    /* output buffer too small */
    char small[4];
    CHECK(halcmd_preprocess("abcdef", small, sizeof(small), NULL, NULL, err, sizeof(err)) == -1);
}

static void test_ini_reader(void)
{
    const char *path = "test_halcmd_parse.ini";
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f == NULL)
        return;
    fputs("# c\n[EMC]\nMACHINE = mill \n[AXIS_0]\n; c\nSCALE=  100.5\nX\n", f);
    fclose(f);
    char *v = halcmd_ini_get(path, "AXIS_0", "SCALE");
    CHECK_EQ_STR(v, "100.5");
    free(v);
    v = halcmd_ini_get(path, "EMC", "MACHINE");
    CHECK_EQ_STR(v, "mill");
    free(v);
    CHECK(halcmd_ini_get(path, "EMC", "SCALE") == NULL);
    CHECK(halcmd_ini_get("/nonexistent/x.ini", "EMC", "SCALE") == NULL);
    remove(path);
}

int main(void)
{
    RUN(test_comments);
    RUN(test_tokens);
    RUN(test_substitution);
    RUN(test_ini_reader);
    return check_summary();
}
