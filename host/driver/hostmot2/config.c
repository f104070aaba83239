/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The per-board config string (spec §12): whitespace-separated tokens,
 * each matched by its keyword prefix; numbers in C base-0 notation. */
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/hm2.h"

void hm2_config_defaults(struct hm2_config *cfg)
{
    memset(cfg, 0, sizeof(*cfg));
    cfg->num_encoders = cfg->num_pwmgens = cfg->num_3pwmgens = cfg->num_rcpwmgens = -1;
    cfg->num_stepgens = cfg->num_leds = cfg->num_bspis = cfg->num_uarts = -1;
    cfg->num_pktuarts = cfg->num_resolvers = cfg->num_dplls = cfg->num_inmuxs = -1;
    cfg->num_inms = cfg->num_outms = cfg->num_xy2mods = cfg->num_ssrs = -1;
    cfg->num_oneshots = cfg->num_sserials = -1;
    cfg->stepgen_width = -1;
}

/* Strict integer: whole text must be a number in int range. */
static int parse_int(const char *s, int *out)
{
    char *end;
    if (*s == '\0')
        return -EINVAL;
    errno = 0;
    long v = strtol(s, &end, 0);
    if (errno || *end != '\0' || v < INT_MIN || v > INT_MAX)
        return -EINVAL;
    *out = (int)v;
    return 0;
}

struct count_key {
    const char *key;
    size_t offset;
};

#define CK(k, f) {k "=", offsetof(struct hm2_config, f)}
static const struct count_key count_keys[] = {
    CK("num_encoders", num_encoders),   CK("num_pwmgens", num_pwmgens),
    CK("num_3pwmgens", num_3pwmgens),   CK("num_rcpwmgens", num_rcpwmgens),
    CK("num_stepgens", num_stepgens),   CK("num_leds", num_leds),
    CK("num_bspis", num_bspis),         CK("num_uarts", num_uarts),
    CK("num_pktuarts", num_pktuarts),   CK("num_resolvers", num_resolvers),
    CK("num_dplls", num_dplls),         CK("num_inmuxs", num_inmuxs),
    CK("num_inms", num_inms),           CK("num_outms", num_outms),
    CK("num_xy2mods", num_xy2mods),     CK("num_ssrs", num_ssrs),
    CK("num_oneshots", num_oneshots),   CK("num_sserials", num_sserials),
    CK("stepgen_width", stepgen_width),
};
#undef CK

static int starts(const char *tok, const char *key)
{
    return strncmp(tok, key, strlen(key)) == 0;
}

static int bad_token(const char *tok, const char *why, char *err, size_t errlen)
{
    if (why)
        snprintf(err, errlen, "invalid token in config string: \"%s\" (%s)", tok, why);
    else
        snprintf(err, errlen, "invalid token in config string: \"%s\"", tok);
    return -EINVAL;
}

static int parse_sserial(const char *tok, struct hm2_config *cfg, char *err, size_t errlen)
{
    /* sserial_port_N=XXXXXXXX */
    const char *p = tok + strlen("sserial_port_");
    if (*p < '0' || *p > '3' || p[1] != '=')
        return bad_token(tok, "port must be 0..3", err, errlen);
    int port = *p - '0';
    const char *modes = p + 2;
    size_t n = strlen(modes);
    if (n == 0 || n > 8)
        return bad_token(tok, "1 to 8 channel modes expected", err, errlen);
    for (size_t i = 0; i < n; i++) {
        if (!isdigit((unsigned char)modes[i]) && modes[i] != 'x' && modes[i] != 'X')
            return bad_token(tok, "channel mode must be 0..9 or x", err, errlen);
    }
    snprintf(cfg->sserial_modes[port], sizeof(cfg->sserial_modes[port]), "%s", modes);
    return 0;
}

char hm2_sserial_mode(const struct hm2_config *cfg, int port, int chan)
{
    if (port < 0 || port >= HM2_MAX_SSERIAL_PORTS || chan < 0 || chan > 7)
        return 'x';
    const char *m = cfg->sserial_modes[port];
    if ((size_t)chan >= strlen(m))
        return '0';
    return m[chan] == 'X' ? 'x' : m[chan];
}

static int parse_token(const char *tok, struct hm2_config *cfg, char *err, size_t errlen)
{
    if (starts(tok, "firmware=")) {
        const char *name = tok + strlen("firmware=");
        if (strlen(name) > HM2_FIRMWARE_NAME_MAX) {
            snprintf(err, errlen, "requested firmware name '%s' is too long (max length is %d)",
                     name, HM2_FIRMWARE_NAME_MAX);
            return -EINVAL;
        }
        if (*name == '\0')
            return bad_token(tok, "empty firmware name", err, errlen);
        snprintf(cfg->firmware, sizeof(cfg->firmware), "%s", name);
        return 0;
    }
    for (size_t i = 0; i < sizeof(count_keys) / sizeof(count_keys[0]); i++) {
        if (!starts(tok, count_keys[i].key))
            continue;
        int v;
        if (parse_int(tok + strlen(count_keys[i].key), &v))
            return bad_token(tok, "not a number", err, errlen);
        if (v < -1)
            return bad_token(tok, "must be -1 (all) or >= 0", err, errlen);
        if (count_keys[i].offset == offsetof(struct hm2_config, stepgen_width) && v < 1)
            return bad_token(tok, "stepgen_width must be >= 1", err, errlen);
        *(int *)((char *)cfg + count_keys[i].offset) = v;
        return 0;
    }
    if (starts(tok, "sserial_port_"))
        return parse_sserial(tok, cfg, err, errlen);
    if (starts(tok, "ssi_chan_") || starts(tok, "biss_chan_") || starts(tok, "fanuc_chan_")) {
        /* Absolute-encoder formats: accepted for compatibility; this driver
         * has no SSI/BiSS/Fanuc module support (see docs/hostmot2.md). */
        if (!strchr(tok, '='))
            return bad_token(tok, NULL, err, errlen);
        return 0;
    }
    if (strcmp(tok, "enable_raw") == 0) {
        cfg->enable_raw = 1;
        return 0;
    }
    return bad_token(tok, NULL, err, errlen);
}

int hm2_config_parse(const char *str, struct hm2_config *cfg, char *err, size_t errlen)
{
    hm2_config_defaults(cfg);
    if (str == NULL)
        return 0;
    /* a config="..." whose quotes reached us (halcmd keeps them on some
     * paths): drop one surrounding pair */
    char unq[1024];
    size_t len = strlen(str);
    if (len >= 2 && str[0] == '"' && str[len - 1] == '"' && len - 2 < sizeof(unq)) {
        memcpy(unq, str + 1, len - 2);
        unq[len - 2] = '\0';
        str = unq;
    }
    const char *p = str;
    while (*p) {
        while (*p && isspace((unsigned char)*p))
            p++;
        if (!*p)
            break;
        const char *start = p;
        while (*p && !isspace((unsigned char)*p))
            p++;
        char tok[256];
        size_t n = (size_t)(p - start);
        if (n >= sizeof(tok)) {
            snprintf(err, errlen, "invalid token in config string: \"%.40s...\" (token too long)",
                     start);
            return -EINVAL;
        }
        memcpy(tok, start, n);
        tok[n] = '\0';
        int r = parse_token(tok, cfg, err, errlen);
        if (r)
            return r;
    }
    return 0;
}
