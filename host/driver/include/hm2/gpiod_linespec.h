/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * gpiod_linespec.h - the "CHIP:lines=A/B/C...[:KEY=N...]" port spec shared
 * by the drivers that put a parallel-port connector on GPIO lines (the EPP
 * backend of epp_port, hal_parport's gpiod backend).
 *
 *   CHIP            anything gpiod_chip_open_lookup() accepts (gpiochip0,
 *                   /dev/gpiochip0, a label or a number)
 *   lines=A/B/...   line offsets in the order of the caller's roles; '/'
 *                   or ',' between them ('/' inside comma-separated array
 *                   modparams); "lines=" may be left out; with allow_nc a
 *                   '-' marks a role with no line
 *   KEY=N           numeric options the caller declares (timeout_us=...)
 *
 * Parsing touches no system resource.
 */
#ifndef HM2_GPIOD_LINESPEC_H
#define HM2_GPIOD_LINESPEC_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GPIOD_LINESPEC_MAX 32
#define GPIOD_LINESPEC_NC (-1) /* offset of a role with no line ('-') */

/* A numeric option: KEY=N with min <= N <= max is stored in *value. */
struct gpiod_linespec_opt {
    const char *key;
    unsigned long min, max;
    unsigned long *value;
};

struct gpiod_linespec {
    char chip[128];
    int n;                           /* roles given */
    int offset[GPIOD_LINESPEC_MAX];  /* line offset, or GPIOD_LINESPEC_NC */
};

/* Parse `spec` (the part after "gpiod:").  `what` starts messages ("gpiod
 * port"), role_name[i] names role i in them (at least max_lines entries).
 * The caller checks the number of roles.  0, or -EINVAL with the reason in
 * err ("gpiod port 'SPEC': bad line offset 'x'", "... line 10 used twice
 * (nAddrStr and nWait)", "... unknown option 'extra'", ...). */
int gpiod_linespec_parse(const char *spec, const char *what, const char *const *role_name,
                         int max_lines, int allow_nc, const struct gpiod_linespec_opt *opts,
                         size_t n_opts, struct gpiod_linespec *out, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* HM2_GPIOD_LINESPEC_H */
