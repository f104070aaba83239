/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pp_cfg.h - hal_parport's cfg string: "ADDR [TYPE] [ADDR [TYPE] ...]".
 *
 * ADDR is one of
 *   N (0..15)               Linux's parallel port N (/dev/parportN, or the
 *                           address in /proc/sys/dev/parport/parportN)
 *   0x378 (>= 16)           an I/O address (C syntax: 0x hex, 0 octal,
 *                           else decimal, as LinuxCNC reads it)
 *   raw:0x378[,HI|,none]    raw port I/O only; HI = ECR base (default
 *                           ADDR+0x400, probed), none = no ECR
 *   ppdev:/dev/parportN     the kernel's ppdev only
 *   gpiod:CHIP:lines=...    17 GPIO lines for pins 1..17 ('-' = not wired)
 *   sim:NAME                the virtual port NAME (vparport)
 * TYPE is in, out (the default), epp or x.  At most 8 ports.
 * Parsing touches nothing; errors say which token and why.
 */
#ifndef PP_CFG_H
#define PP_CFG_H

#include <stddef.h>

#include "pp_port.h"

#define PP_MAX_PORTS 8

enum pp_addr_kind { PP_ADDR_INDEX, PP_ADDR_IO, PP_ADDR_RAW, PP_ADDR_PPDEV, PP_ADDR_GPIOD,
                    PP_ADDR_SIM };

struct pp_cfg_port {
    enum pp_addr_kind kind;
    long addr;       /* INDEX: N; IO/RAW: base */
    long hi;         /* IO/RAW: ECR base, 0 = addr+0x400 probed, -1 = none */
    char spec[256];  /* PPDEV path, GPIOD spec, SIM name */
    char text[300];  /* the token as given, for messages */
    enum pp_mode mode;
};

struct pp_cfg {
    int n;
    struct pp_cfg_port port[PP_MAX_PORTS];
};

int pp_cfg_parse(const char *cfg, struct pp_cfg *out, char *err, size_t errlen);
const char *pp_mode_name(enum pp_mode m);

#endif /* PP_CFG_H */
