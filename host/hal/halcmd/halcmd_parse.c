/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_parse.c - comments, variable substitution and tokenizing of one
 * halcmd line (see halcmd_parse.h).
 */
#define _GNU_SOURCE
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "halcmd_parse.h"

#define SETERR(...)                             \
    do {                                        \
        if (err != NULL && errlen > 0)          \
            snprintf(err, errlen, __VA_ARGS__); \
    } while (0)

static int put(char *out, size_t outlen, size_t *n, const char *s, size_t len)
{
    if (*n + len + 1 > outlen)
        return -1;
    memcpy(out + *n, s, len);
    *n += len;
    out[*n] = '\0';
    return 0;
}

int halcmd_preprocess(const char *line, char *out, size_t outlen, halcmd_ini_lookup_fn ini,
                      void *ini_ctx, char *err, size_t errlen)
{
    size_t n = 0;
    if (outlen == 0)
        return -1;
    out[0] = '\0';
    for (const char *p = line; *p;) {
        if (*p == '#' || *p == '\n' || *p == '\r')
            break;
        if (*p == '$') {
            const char *start = p + 1, *end;
            int paren = 0;
            if (*start == '(') {
                paren = 1;
                start++;
                end = strchr(start, ')');
                if (end == NULL) {
                    SETERR("missing ')' after '$('");
                    return -1;
                }
            } else {
                end = start;
                while (isalnum((unsigned char)*end) || *end == '_')
                    end++;
            }
            if (end == start) {
                if (put(out, outlen, &n, p, 1))
                    goto toolong;
                p++;
                continue;
            }
            char name[256];
            size_t len = (size_t)(end - start);
            if (len >= sizeof(name)) {
                SETERR("variable name too long");
                return -1;
            }
            memcpy(name, start, len);
            name[len] = '\0';
            const char *val = getenv(name);
            if (val == NULL) {
                SETERR("Environment variable '%s' not set", name);
                return -1;
            }
            if (put(out, outlen, &n, val, strlen(val)))
                goto toolong;
            p = end + paren;
            continue;
        }
        if (*p == '[') {
            const char *close = strchr(p + 1, ']');
            if (close != NULL && close > p + 1) {
                const char *kstart = close + 1, *kend = kstart;
                while (*kend && (isalnum((unsigned char)*kend) || *kend == '_' || *kend == '-' ||
                                 *kend == '.'))
                    kend++;
                if (kend > kstart) {
                    char sec[256], key[256];
                    size_t sl = (size_t)(close - p - 1), kl = (size_t)(kend - kstart);
                    if (sl >= sizeof(sec) || kl >= sizeof(key)) {
                        SETERR("INI reference too long");
                        return -1;
                    }
                    memcpy(sec, p + 1, sl);
                    sec[sl] = '\0';
                    memcpy(key, kstart, kl);
                    key[kl] = '\0';
                    char *val = ini ? ini(sec, key, ini_ctx) : NULL;
                    if (val == NULL) {
                        SETERR("Ini variable '[%s]%s' not found.", sec, key);
                        return -1;
                    }
                    int rc = put(out, outlen, &n, val, strlen(val));
                    free(val);
                    if (rc)
                        goto toolong;
                    p = kend;
                    continue;
                }
            }
        }
        if (put(out, outlen, &n, p, 1))
            goto toolong;
        p++;
    }
    return 0;
toolong:
    SETERR("line too long");
    return -1;
}

int halcmd_tokenize(char *line, char **tokens, int max, char *err, size_t errlen)
{
    int n = 0;
    char *p = line;
    for (;;) {
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '\0')
            break;
        if (n >= max) {
            SETERR("too many tokens (at most %d)", max);
            return -1;
        }
        tokens[n++] = p;
        int inq = 0;
        while (*p && (inq || (*p != ' ' && *p != '\t'))) {
            if (*p == '"')
                inq = !inq;
            p++;
        }
        if (inq) {
            SETERR("unterminated quoted string");
            return -1;
        }
        if (*p)
            *p++ = '\0';
    }
    return n;
}

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    char *e = s + strlen(s);
    while (e > s && isspace((unsigned char)e[-1]))
        *--e = '\0';
    return s;
}

char *halcmd_ini_get(const char *path, const char *section, const char *key)
{
    FILE *f = fopen(path, "r");
    if (f == NULL)
        return NULL;
    char buf[4096];
    int insec = 0;
    char *result = NULL;
    while (result == NULL && fgets(buf, sizeof(buf), f)) {
        char *s = trim(buf);
        if (*s == '#' || *s == ';' || *s == '\0')
            continue;
        if (*s == '[') {
            char *close = strchr(s, ']');
            if (close) {
                *close = '\0';
                insec = strcmp(s + 1, section) == 0;
            }
            continue;
        }
        if (!insec)
            continue;
        char *eq = strchr(s, '=');
        if (eq == NULL)
            continue;
        *eq = '\0';
        if (strcmp(trim(s), key) == 0)
            result = strdup(trim(eq + 1));
    }
    fclose(f);
    return result;
}
