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
    if (strcmp(section, "HOSTMOT2") == 0 && strcmp(key, "DRIVER") == 0)
        return strdup("hm2_pci");
    if (strcmp(section, "HOSTMOT2") == 0 && strcmp(key, "BOARD") == 0)
        return strdup("5i20");
    if (strcmp(section, "") == 0 && strcmp(key, "SCALE") == 0)
        return strdup("any");
    if (strcmp(section, "S") == 0 && strcmp(key, "a b") == 0)
        return strdup("spaced");
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
    CHECK_EQ_STR(err, "Environment variable 'HM_TEST_NOPE' not found.");
    CHECK(halcmd_preprocess("setp a $(HM_TEST_VAR", buf, sizeof(buf), NULL, NULL, err,
                            sizeof(err)) == -1);
    /* output buffer too small */
    char small[4];
    CHECK(halcmd_preprocess("abcdef", small, sizeof(small), NULL, NULL, err, sizeof(err)) == -1);
}

/* Recorded from LinuxCNC 2.9's halcmd (lcnc-halrun -k -i t.ini): the
 * message for each line, or the substituted result. */
static void test_linuxcnc_rules(void)
{
    static const struct {
        const char *in, *out, *err;
    } cases[] = {
        {"loadrt [HOSTMOT2](DRIVER)", "loadrt hm2_pci", NULL},
        {"net x hm2_[HOSTMOT2](BOARD).0.led", "net x hm2_5i20.0.led", NULL},
        {"p [HOSTMOT2]BOARD,x", "p 5i20,x", NULL},
        {"p [HOSTMOT2]BOARD/x", "p 5i20/x", NULL},
        {"p [HOSTMOT2](BOARD)(x)", "p 5i20(x)", NULL},
        {"p [HOSTMOT2]BOARD]x", "p 5i20]x", NULL},
        {"p []SCALE", "p any", NULL},
        {"p [](SCALE)", "p any", NULL},
        {"p [S](a b)", "p spaced", NULL},
        {"p [HOSTMOT2]BOARD-x", NULL, "Ini variable '[HOSTMOT2]BOARD-x' not found."},
        {"p [HOSTMOT2]BOARD.x", NULL, "Ini variable '[HOSTMOT2]BOARD.x' not found."},
        {"p [HOSTMOT2]BOARD_x", NULL, "Ini variable '[HOSTMOT2]BOARD_x' not found."},
        {"p [HOSTMOT2](NOPE)", NULL, "Ini variable '[HOSTMOT2]NOPE' not found."},
        {"p [HOSTMOT2]()", NULL, "Empty variable name."},
        {"p [HOSTMOT2]", NULL, "Empty variable name."},
        {"p [HOSTMOT2] x", NULL, "Empty variable name."},
        {"p a [x] b", NULL, "Empty variable name."},
        {"p [", NULL, "Missing close square bracket."},
        {"p $", NULL, "Empty variable name."},
        {"p a$ b", NULL, "Empty variable name."},
        {"p $()", NULL, "Empty variable name."},
        {"p $(HM_TEST_VAR", NULL, "Missing close parenthesis."},
        {"p $HM_TEST_VAR/x", "p sig1/x", NULL},
        {"p $HM_TEST_VAR,x", "p sig1,x", NULL},
        {"p $HM_TEST_VAR.x", NULL, "Environment variable 'HM_TEST_VAR.x' not found."},
        {"p $HM_TEST_VAR-x", NULL, "Environment variable 'HM_TEST_VAR-x' not found."},
        {"p $HM_TEST_VAR$HM_TEST_VAR", "p sig1sig1", NULL},
        {"p \"$HM_TEST_VAR\"", "p \"sig1\"", NULL},
        {"p '$HM_TEST_VAR'", "p 'sig1'", NULL},
        /* '#' starts a comment only outside quotes */
        {"p \"a#b\" # c", "p \"a#b\" ", NULL},
        {"p 'a # b'", "p 'a # b'", NULL},
        {"p a#b", "p a", NULL},
    };
    setenv("HM_TEST_VAR", "sig1", 1);
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        char buf[256], err[128] = "";
        int rc = halcmd_preprocess(cases[i].in, buf, sizeof(buf), ini_fake, NULL, err,
                                   sizeof(err));
        if (cases[i].out != NULL) {
            CHECK_EQ_INT(rc, 0);
            CHECK_EQ_STR(buf, cases[i].out);
        } else {
            CHECK_EQ_INT(rc, -1);
            CHECK_EQ_STR(err, cases[i].err);
        }
    }
}

static void test_quotes(void)
{
    char t[8][64];
    /* single quotes group too; a quote closes only its own kind */
    CHECK_EQ_INT(tok("print 'a b' \"c'd\" 'e\"f'", t, 8), 4);
    CHECK_EQ_STR(t[1], "'a b'");
    CHECK_EQ_STR(t[2], "\"c'd\"");
    CHECK_EQ_STR(t[3], "'e\"f'");
    CHECK_EQ_INT(tok("print a\"b c\"d", t, 8), 2);
    CHECK_EQ_STR(t[1], "a\"b c\"d");
    /* no backslash escapes inside quotes */
    CHECK_EQ_INT(tok("print \"a\\\"b\"", t, 8), -1);
    CHECK_EQ_INT(tok("print x'y", t, 8), -1);
}

/* Logical lines of a file given as a string. */
static int read_all(const char *text, size_t len, char lines[][64], int *linenos, int max,
                    char *err, size_t errlen, size_t buflen)
{
    FILE *f = fmemopen((void *)text, len, "r");
    if (f == NULL)
        return -2;
    char *buf = malloc(buflen);
    int n = 0, linenum = 0, rc;
    while (n < max && (rc = halcmd_read_line(f, buf, buflen, &linenum, err, errlen)) == 1) {
        snprintf(lines[n], 64, "%s", buf);
        linenos[n++] = linenum;
    }
    free(buf);
    fclose(f);
    return rc < 0 ? -1 : n;
}

static void test_read_line(void)
{
    char l[8][64], err[128];
    int ln[8];
    /* continuation joins with nothing in between (LinuxCNC 2.9:
     * names=d1\ + ,d2 loads d1 and d2); errors name the last line */
    const char *a = "loadrt and2 names=d1\\\n,d2\nnewsig e \\\n  float\r\nlast";
    CHECK_EQ_INT(read_all(a, strlen(a), l, ln, 8, err, sizeof(err), 256), 3);
    CHECK_EQ_STR(l[0], "loadrt and2 names=d1,d2");
    CHECK_EQ_INT(ln[0], 2);
    CHECK_EQ_STR(l[1], "newsig e   float");
    CHECK_EQ_INT(ln[1], 4);
    CHECK_EQ_STR(l[2], "last");
    CHECK_EQ_INT(ln[2], 5);
    /* empty lines count */
    CHECK_EQ_INT(read_all("\n\nx\n", 4, l, ln, 8, err, sizeof(err), 256), 3);
    CHECK_EQ_INT(ln[2], 3);
    /* a line longer than the buffer is an error naming the line */
    char longl[300];
    memset(longl, 'x', sizeof(longl));
    memcpy(longl, "ok\n", 3);
    CHECK_EQ_INT(read_all(longl, sizeof(longl), l, ln, 8, err, sizeof(err), 256), -1);
    CHECK_EQ_STR(err, "line too long (more than 255 characters)");
    /* endless continuations are bounded the same way */
    static char cont[70000 * 3];
    for (size_t i = 0; i < 70000; i++)
        memcpy(cont + 3 * i, "a\\\n", 3);
    CHECK_EQ_INT(read_all(cont, sizeof(cont), l, ln, 8, err, sizeof(err), HALCMD_MAX_LINE), -1);
    CHECK_EQ_STR(err, "line too long (more than 65535 characters)");
    /* binary data */
    CHECK_EQ_INT(read_all("ab\0cd\n", 6, l, ln, 8, err, sizeof(err), 256), -1);
    CHECK_EQ_STR(err, "line contains a NUL byte (not a text file?)");
    /* a trailing backslash at the end of the file continues into nothing */
    CHECK_EQ_INT(read_all("a\\", 2, l, ln, 8, err, sizeof(err), 256), 1);
    CHECK_EQ_STR(l[0], "a");
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
    v = halcmd_ini_get(path, "", "SCALE"); /* any section */
    CHECK_EQ_STR(v, "100.5");
    free(v);
    CHECK(halcmd_ini_get("/dev/zero", "EMC", "SCALE") == NULL); /* not a file */
    CHECK(halcmd_ini_get("/nonexistent/x.ini", "EMC", "SCALE") == NULL);
    remove(path);
}

int main(void)
{
    RUN(test_comments);
    RUN(test_tokens);
    RUN(test_substitution);
    RUN(test_linuxcnc_rules);
    RUN(test_quotes);
    RUN(test_read_line);
    RUN(test_ini_reader);
    return check_summary();
}
