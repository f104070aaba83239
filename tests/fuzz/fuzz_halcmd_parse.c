/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * libFuzzer target: halcmd's line preprocessing (comments, $ENV, $(ENV),
 * [SECTION]KEY) and tokenizing, on arbitrary bytes.  Build:
 *   clang -g -fsanitize=fuzzer,address,undefined -Ihost/hal/halcmd \
 *         tests/fuzz/fuzz_halcmd_parse.c host/hal/halcmd/halcmd_parse.c
 * (tests/fuzz/test_fuzz.py does this and runs it briefly).
 */
#include <stdint.h>
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

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 8192)
        return 0;
    char *line = malloc(size + 1);
    if (line == NULL)
        return 0;
    memcpy(line, data, size);
    line[size] = '\0';
    size_t outlen = 1 + (size % 4096);
    char *out = malloc(outlen);
    char err[256];
    char *tokens[64];
    if (out != NULL &&
        halcmd_preprocess(line, out, outlen, fake_ini, NULL, err, sizeof(err)) == 0) {
        int n = halcmd_tokenize(out, tokens, 64, err, sizeof(err));
        for (int i = 0; i < n; i++) {
            /* every token is a NUL-terminated non-empty string inside out */
            if (tokens[i] < out || tokens[i] >= out + outlen || tokens[i][0] == '\0')
                abort();
        }
    }
    free(out);
    free(line);
    return 0;
}
