/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * libFuzzer target: halcmd's input handling on arbitrary bytes, read as a
 * HAL file: logical lines (backslash continuation, length bound, NUL
 * bytes), comments, $ENV / $(ENV) / [SECTION]KEY / [SECTION](KEY)
 * substitution and tokenizing.  The first byte picks the buffer sizes, so
 * the bounds are exercised with small buffers too.  Build:
 *   clang -g -fsanitize=fuzzer,address,undefined -Ihost/hal/halcmd \
 *         tests/fuzz/fuzz_halcmd_parse.c host/hal/halcmd/halcmd_parse.c
 * (tests/fuzz/test_fuzz.py does this and runs it over tests/fuzz/corpus/halcmd).
 */
#define _GNU_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "halcmd_parse.h"

static char *fake_ini(const char *section, const char *key, void *ctx)
{
    (void)ctx;
    /* Deterministic, sometimes long, sometimes missing. */
    size_t n = strlen(section) + strlen(key);
    if (n % 3 == 0)
        return NULL;
    char *v = malloc(n * 7 + 2);
    if (v == NULL)
        return NULL;
    for (size_t i = 0; i < n * 7 + 1; i++)
        v[i] = (char)('a' + i % 26);
    v[n * 7 + 1] = '\0';
    return v;
}

static void check_line(char *line, size_t outlen)
{
    char *out = malloc(outlen);
    char err[256];
    char *tokens[64];
    if (out == NULL)
        return;
    if (halcmd_preprocess(line, out, outlen, fake_ini, NULL, err, sizeof(err)) == 0) {
        if (strlen(out) >= outlen)
            abort();
        int n = halcmd_tokenize(out, tokens, 64, err, sizeof(err));
        for (int i = 0; i < n; i++) {
            /* every token is a NUL-terminated non-empty string inside out */
            if (tokens[i] < out || tokens[i] >= out + outlen || tokens[i][0] == '\0')
                abort();
        }
    } else if (err[0] == '\0') {
        abort(); /* every failure says why */
    }
    free(out);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > 65536)
        return 0;
    size_t buflen = 2 + data[0] % 512;
    size_t outlen = 1 + (data[0] * 7u) % 1024;
    FILE *f = fmemopen((void *)(data + 1), size - 1, "r");
    if (f == NULL)
        return 0;
    char *line = malloc(buflen);
    char err[256];
    int linenum = 0, prev = 0, rc;
    while (line != NULL && (rc = halcmd_read_line(f, line, buflen, &linenum, err, sizeof(err))) == 1) {
        if (strlen(line) >= buflen || linenum <= prev)
            abort(); /* bounded, and line numbers always advance */
        prev = linenum;
        check_line(line, outlen);
    }
    free(line);
    fclose(f);
    return 0;
}
