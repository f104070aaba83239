/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_parse.c - reading, comments, variable substitution and tokenizing
 * of halcmd lines (see halcmd_parse.h).  Every buffer has a fixed bound, so
 * a hostile file (no newline, endless continuations, binary data) ends in
 * an error instead of unbounded growth.
 */
#define _GNU_SOURCE
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "halcmd_parse.h"

#define SETERR(...)                             \
    do {                                        \
        if (err != NULL && errlen > 0)          \
            snprintf(err, errlen, __VA_ARGS__); \
    } while (0)

/* ---- logical lines ---------------------------------------------------------- */

int halcmd_read_line(FILE *f, char *buf, size_t buflen, int *linenum, char *err, size_t errlen)
{
    size_t n = 0;
    int got = 0; /* read at least one byte (or line end) */
    if (buflen < 2) {
        SETERR("line buffer too small");
        return -1;
    }
    buf[0] = '\0';
    for (;;) {
        int c = getc(f);
        if (c == EOF) {
            if (ferror(f)) {
                SETERR("read error: %s", strerror(errno ? errno : EIO));
                return -1;
            }
            if (got)
                (*linenum)++;
            break;
        }
        got = 1;
        if (c == '\n') {
            (*linenum)++;
            if (n > 0 && buf[n - 1] == '\r')
                buf[--n] = '\0';
            if (n > 0 && buf[n - 1] == '\\') {
                /* continued: drop the backslash, join with nothing */
                buf[--n] = '\0';
                got = 0;
                continue;
            }
            return 1;
        }
        if (c == '\0') {
            (*linenum)++;
            SETERR("line contains a NUL byte (not a text file?)");
            return -1;
        }
        if (n + 1 >= buflen) {
            (*linenum)++;
            SETERR("line too long (more than %zu characters)", buflen - 1);
            return -1;
        }
        buf[n++] = (char)c;
        buf[n] = '\0';
    }
    /* End of file: a last line without newline still counts; a trailing
     * backslash continues into nothing. */
    if (n > 0 && buf[n - 1] == '\r')
        buf[--n] = '\0';
    int joined = n > 0 && buf[n - 1] == '\\';
    if (joined)
        buf[--n] = '\0';
    return (got || n > 0 || joined) ? 1 : 0;
}

/* ---- substitution ------------------------------------------------------------- */

static int put(char *out, size_t outlen, size_t *n, const char *s, size_t len)
{
    if (*n + len + 1 > outlen)
        return -1;
    memcpy(out + *n, s, len);
    *n += len;
    out[*n] = '\0';
    return 0;
}

static int name_char(char c)
{
    return isalnum((unsigned char)c) || c == '_' || c == '-' || c == '.';
}

/* Copy [start, end) into a bounded name buffer. */
static int take_name(char *dst, size_t dstlen, const char *start, const char *end)
{
    size_t len = (size_t)(end - start);
    if (len >= dstlen)
        return -1;
    memcpy(dst, start, len);
    dst[len] = '\0';
    return 0;
}

/* $NAME or $(NAME) at p (p[0] == '$'); *endp is set past it. */
static int subst_env(const char *p, const char **endp, char *out, size_t outlen, size_t *n,
                     char *err, size_t errlen)
{
    const char *start = p + 1, *end;
    int paren = *start == '(';
    if (paren) {
        start++;
        end = strchr(start, ')');
        if (end == NULL) {
            SETERR("Missing close parenthesis.");
            return -1;
        }
    } else {
        for (end = start; name_char(*end); end++)
            ;
    }
    if (end == start) {
        SETERR("Empty variable name.");
        return -1;
    }
    char name[256];
    if (take_name(name, sizeof(name), start, end) != 0) {
        SETERR("Variable name too long.");
        return -1;
    }
    const char *val = getenv(name);
    if (val == NULL) {
        SETERR("Environment variable '%s' not found.", name);
        return -1;
    }
    if (put(out, outlen, n, val, strlen(val)) != 0) {
        SETERR("line too long after substitution (more than %zu characters)", outlen - 1);
        return -1;
    }
    *endp = end + paren;
    return 0;
}

/* [SECTION]KEY or [SECTION](KEY) at p (p[0] == '['). */
static int subst_ini(const char *p, const char **endp, char *out, size_t outlen, size_t *n,
                     halcmd_ini_lookup_fn ini, void *ini_ctx, char *err, size_t errlen)
{
    const char *close = strchr(p + 1, ']');
    if (close == NULL) {
        SETERR("Missing close square bracket.");
        return -1;
    }
    const char *kstart = close + 1, *kend;
    int paren = *kstart == '(';
    if (paren) {
        kstart++;
        kend = strchr(kstart, ')');
        if (kend == NULL) {
            SETERR("Missing close parenthesis.");
            return -1;
        }
    } else {
        for (kend = kstart; name_char(*kend); kend++)
            ;
    }
    if (kend == kstart) {
        SETERR("Empty variable name.");
        return -1;
    }
    char sec[256], key[256];
    if (take_name(sec, sizeof(sec), p + 1, close) != 0 ||
        take_name(key, sizeof(key), kstart, kend) != 0) {
        SETERR("Variable name too long.");
        return -1;
    }
    char *val = ini != NULL ? ini(sec, key, ini_ctx) : NULL;
    if (val == NULL) {
        SETERR("Ini variable '[%s]%s' not found.", sec, key);
        return -1;
    }
    int rc = put(out, outlen, n, val, strlen(val));
    free(val);
    if (rc != 0) {
        SETERR("line too long after substitution (more than %zu characters)", outlen - 1);
        return -1;
    }
    *endp = kend + paren;
    return 0;
}

int halcmd_preprocess(const char *line, char *out, size_t outlen, halcmd_ini_lookup_fn ini,
                      void *ini_ctx, char *err, size_t errlen)
{
    size_t n = 0;
    char quote = 0;
    if (outlen == 0) {
        SETERR("no room for the line");
        return -1;
    }
    out[0] = '\0';
    for (const char *p = line; *p;) {
        if (quote == 0 && (*p == '#' || *p == '\n' || *p == '\r'))
            break;
        if (*p == '$') {
            if (subst_env(p, &p, out, outlen, &n, err, errlen) != 0)
                return -1;
            continue;
        }
        if (*p == '[') {
            if (subst_ini(p, &p, out, outlen, &n, ini, ini_ctx, err, errlen) != 0)
                return -1;
            continue;
        }
        if (*p == '"' || *p == '\'') {
            if (quote == 0)
                quote = *p;
            else if (quote == *p)
                quote = 0;
        }
        if (put(out, outlen, &n, p, 1) != 0) {
            SETERR("line too long (more than %zu characters)", outlen - 1);
            return -1;
        }
        p++;
    }
    return 0;
}

/* ---- tokens ------------------------------------------------------------------------ */

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
        char quote = 0;
        while (*p && (quote || (*p != ' ' && *p != '\t'))) {
            if (quote == 0 && (*p == '"' || *p == '\''))
                quote = *p;
            else if (quote == *p)
                quote = 0;
            p++;
        }
        if (quote) {
            SETERR("unterminated quoted string");
            return -1;
        }
        if (*p)
            *p++ = '\0';
    }
    return n;
}

/* ---- INI files ------------------------------------------------------------------- */

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
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || !S_ISREG(st.st_mode)) {
        fclose(f); /* a device or directory is not an INI file */
        return NULL;
    }
    char *buf = NULL;
    size_t cap = 0;
    int insec = section[0] == '\0';
    char *result = NULL;
    while (result == NULL && getline(&buf, &cap, f) >= 0) {
        char *s = trim(buf);
        if (*s == '#' || *s == ';' || *s == '\0')
            continue;
        if (*s == '[') {
            char *close = strchr(s, ']');
            if (close != NULL && section[0] != '\0') {
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
    free(buf);
    fclose(f);
    return result;
}
