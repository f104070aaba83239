/* SPDX-License-Identifier: GPL-2.0-or-later */
/* pp_cfg.c - hal_parport's cfg string (pp_cfg.h). */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pp_cfg.h"

static const char *const mode_names[] = {"out", "in", "epp", "x"};

const char *pp_mode_name(enum pp_mode m)
{
    return (unsigned)m < 4 ? mode_names[m] : "?";
}

static int mode_of(const char *tok)
{
    for (int i = 0; i < 4; i++)
        if (!strcmp(tok, mode_names[i]))
            return i;
    return -1;
}

/* A whole-token unsigned number in C syntax (base 0), at most max. */
static int number(const char *s, unsigned long max, long *out)
{
    char *end;
    if (!isdigit((unsigned char)*s))
        return -1;
    errno = 0;
    unsigned long v = strtoul(s, &end, 0);
    if (errno || *end || v > max)
        return -1;
    *out = (long)v;
    return 0;
}

static int parse_raw(const char *rest, struct pp_cfg_port *p)
{
    char buf[64];
    size_t n = strlen(rest);
    if (n >= sizeof(buf))
        return -1;
    memcpy(buf, rest, n + 1);
    char *comma = strchr(buf, ',');
    if (comma)
        *comma++ = '\0';
    if (number(buf, 0xfffd, &p->addr) || p->addr < 16)
        return -1;
    p->hi = 0;
    if (comma) {
        if (!strcmp(comma, "none"))
            p->hi = -1;
        else if (number(comma, 0xfffd, &p->hi) || p->hi < 16)
            return -1;
    }
    return 0;
}

static int parse_addr(const char *tok, struct pp_cfg_port *p, char *err, size_t errlen)
{
    memset(p, 0, sizeof(*p));
    snprintf(p->text, sizeof(p->text), "%s", tok);
    const char *colon = strchr(tok, ':');
    if (!colon) {
        if (number(tok, 0xfffd, &p->addr)) {
            snprintf(err, errlen,
                     "cfg: bad port address '%s' (want a Linux port number 0-15, an I/O "
                     "address such as 0x378, raw:ADDR, ppdev:DEVICE, gpiod:CHIP:LINES or "
                     "sim:NAME; the type in, out, epp or x follows an address)",
                     tok);
            return -EINVAL;
        }
        p->kind = p->addr < 16 ? PP_ADDR_INDEX : PP_ADDR_IO;
        p->hi = 0;
        return 0;
    }
    size_t klen = (size_t)(colon - tok);
    const char *rest = colon + 1;
    if (strlen(rest) >= sizeof(p->spec)) {
        snprintf(err, errlen, "cfg: port '%s' is too long", tok);
        return -EINVAL;
    }
    if (klen == 3 && !strncmp(tok, "raw", 3)) {
        p->kind = PP_ADDR_RAW;
        if (parse_raw(rest, p)) {
            snprintf(err, errlen,
                     "cfg: bad raw port '%s' (want raw:ADDR, raw:ADDR,ECR_ADDR or "
                     "raw:ADDR,none with I/O addresses 0x10..0xfffd)",
                     tok);
            return -EINVAL;
        }
        return 0;
    }
    if (klen == 5 && !strncmp(tok, "ppdev", 5))
        p->kind = PP_ADDR_PPDEV;
    else if (klen == 5 && !strncmp(tok, "gpiod", 5))
        p->kind = PP_ADDR_GPIOD;
    else if (klen == 3 && !strncmp(tok, "sim", 3))
        p->kind = PP_ADDR_SIM;
    else {
        snprintf(err, errlen,
                 "cfg: unknown port kind in '%s' (want raw:, ppdev:, gpiod: or sim:)", tok);
        return -EINVAL;
    }
    if (!*rest) {
        snprintf(err, errlen, "cfg: port '%s' names nothing after the ':'", tok);
        return -EINVAL;
    }
    snprintf(p->spec, sizeof(p->spec), "%s", rest);
    return 0;
}

static int same_port(const struct pp_cfg_port *a, const struct pp_cfg_port *b)
{
    if (a->kind != b->kind)
        return (a->kind == PP_ADDR_IO || a->kind == PP_ADDR_RAW) &&
               (b->kind == PP_ADDR_IO || b->kind == PP_ADDR_RAW) && a->addr == b->addr;
    switch (a->kind) {
    case PP_ADDR_INDEX:
    case PP_ADDR_IO:
    case PP_ADDR_RAW:
        return a->addr == b->addr;
    default:
        return !strcmp(a->spec, b->spec);
    }
}

int pp_cfg_parse(const char *cfg, struct pp_cfg *out, char *err, size_t errlen)
{
    memset(out, 0, sizeof(*out));
    const char *s = cfg ? cfg : "";
    char tok[300];
    int have_type = 0;
    for (;;) {
        while (isspace((unsigned char)*s))
            s++;
        if (!*s)
            break;
        size_t n = 0;
        while (s[n] && !isspace((unsigned char)s[n]))
            n++;
        if (n >= sizeof(tok)) {
            snprintf(err, errlen, "cfg: word '%.40s...' is too long", s);
            return -EINVAL;
        }
        memcpy(tok, s, n);
        tok[n] = '\0';
        s += n;
        int m = mode_of(tok);
        if (m >= 0) {
            if (out->n == 0 || have_type) {
                snprintf(err, errlen, "cfg: type '%s' must follow a port address%s", tok,
                         out->n ? " (one type per port)" : "");
                return -EINVAL;
            }
            out->port[out->n - 1].mode = (enum pp_mode)m;
            have_type = 1;
            continue;
        }
        if (out->n == PP_MAX_PORTS) {
            snprintf(err, errlen, "cfg: more than %d ports ('%s')", PP_MAX_PORTS, tok);
            return -EINVAL;
        }
        struct pp_cfg_port *p = &out->port[out->n];
        int r = parse_addr(tok, p, err, errlen);
        if (r)
            return r;
        p->mode = PP_MODE_OUT;
        for (int i = 0; i < out->n; i++)
            if (same_port(&out->port[i], p)) {
                snprintf(err, errlen, "cfg: port '%s' is given twice (ports %d and %d)", tok, i,
                         out->n);
                return -EINVAL;
            }
        out->n++;
        have_type = 0;
    }
    if (out->n == 0) {
        snprintf(err, errlen, "cfg: no ports configured (e.g. cfg=\"0x378 out\")");
        return -EINVAL;
    }
    return 0;
}
