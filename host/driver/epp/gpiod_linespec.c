/* SPDX-License-Identifier: GPL-2.0-or-later */
#define _GNU_SOURCE
/* gpiod_linespec.c - parser of "CHIP:lines=A/B/...[:KEY=N]" (see the header). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/gpiod_linespec.h"

static int parse_opt(const char *spec, const char *what, const char *tok,
                     const struct gpiod_linespec_opt *opts, size_t n_opts, char *err,
                     size_t errlen)
{
    const char *eq = strchr(tok, '=');
    for (size_t i = 0; eq && i < n_opts; i++) {
        size_t klen = strlen(opts[i].key);
        if ((size_t)(eq - tok) != klen || strncmp(tok, opts[i].key, klen) != 0)
            continue;
        const char *v = eq + 1;
        char *end;
        unsigned long n = strtoul(v, &end, 10);
        if (*v == '\0' || *v == '-' || *v == '+' || *end || n < opts[i].min ||
            n > opts[i].max) {
            snprintf(err, errlen, "%s '%s': bad %s '%s' (%lu..%lu)", what, spec, opts[i].key, v,
                     opts[i].min, opts[i].max);
            return -EINVAL;
        }
        *opts[i].value = n;
        return 0;
    }
    return 1; /* not an option */
}

static int parse_lines(const char *spec, const char *what, const char *const *role_name,
                       int max_lines, int allow_nc, const char *list, struct gpiod_linespec *out,
                       char *err, size_t errlen)
{
    char lb[256], *save = NULL;
    snprintf(lb, sizeof(lb), "%s", list);
    for (char *o = strtok_r(lb, "/,", &save); o; o = strtok_r(NULL, "/,", &save)) {
        if (out->n >= max_lines) {
            snprintf(err, errlen, "%s '%s': more than %d line offsets", what, spec, max_lines);
            return -EINVAL;
        }
        if (allow_nc && strcmp(o, "-") == 0) {
            out->offset[out->n++] = GPIOD_LINESPEC_NC;
            continue;
        }
        char *end;
        unsigned long v = strtoul(o, &end, 10);
        if (*end || !*o || o[0] == '-' || o[0] == '+' || v > 4096) {
            snprintf(err, errlen, "%s '%s': bad line offset '%s'", what, spec, o);
            return -EINVAL;
        }
        for (int k = 0; k < out->n; k++)
            if (out->offset[k] == (int)v) {
                snprintf(err, errlen, "%s '%s': line %lu used twice (%s and %s)", what, spec, v,
                         role_name[k], role_name[out->n]);
                return -EINVAL;
            }
        out->offset[out->n++] = (int)v;
    }
    return 0;
}

int gpiod_linespec_parse(const char *spec, const char *what, const char *const *role_name,
                         int max_lines, int allow_nc, const struct gpiod_linespec_opt *opts,
                         size_t n_opts, struct gpiod_linespec *out, char *err, size_t errlen)
{
    char buf[256];
    memset(out, 0, sizeof(*out));
    if (max_lines > GPIOD_LINESPEC_MAX)
        max_lines = GPIOD_LINESPEC_MAX;
    if (!spec || strlen(spec) >= sizeof(buf)) {
        snprintf(err, errlen, "%s: spec missing or too long", what);
        return -EINVAL;
    }
    snprintf(buf, sizeof(buf), "%s", spec);
    char *save = NULL;
    char *tok = strtok_r(buf, ":", &save);
    if (!tok || !*tok || spec[0] == ':') {
        snprintf(err, errlen, "%s '%s': missing chip (gpiod:gpiochip0:lines=...)", what, spec);
        return -EINVAL;
    }
    snprintf(out->chip, sizeof(out->chip), "%s", tok);
    int have_lines = 0;
    while ((tok = strtok_r(NULL, ":", &save)) != NULL) {
        int r = parse_opt(spec, what, tok, opts, n_opts, err, errlen);
        if (r <= 0) {
            if (r < 0)
                return r;
            continue;
        }
        if (have_lines) {
            snprintf(err, errlen, "%s '%s': unknown option '%s'", what, spec, tok);
            return -EINVAL;
        }
        const char *list = strncmp(tok, "lines=", 6) == 0 ? tok + 6 : tok;
        r = parse_lines(spec, what, role_name, max_lines, allow_nc, list, out, err, errlen);
        if (r)
            return r;
        have_lines = 1;
    }
    return 0;
}
