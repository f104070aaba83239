/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Message formatting for the core: every board message is prefixed with
 * "hm2/<llio-name>: " as LinuxCNC prints it; the sink decides where it goes.
 * hm2_log_printf is the same formatting for the board drivers (backends/),
 * which write their own prefixes and stay silent without a sink. */
#include <stdio.h>

#include "hm2/hm2.h"

static void emit(hm2_log_fn log, void *ctx, int level, const char *prefix, const char *fmt,
                 va_list ap)
{
    char line[512];
    int n = snprintf(line, sizeof(line), "%s", prefix);
    if (n < 0 || (size_t)n >= sizeof(line))
        n = 0;
    vsnprintf(line + n, sizeof(line) - (size_t)n, fmt, ap);
    if (log)
        log(ctx, level, line);
    else
        fprintf(stderr, "%s\n", line);
}

void hm2_msg(const hostmot2_t *hm2, int level, const char *fmt, ...)
{
    char prefix[HM2_LLIO_NAME_LEN + 8];
    snprintf(prefix, sizeof(prefix), "hm2/%s: ", hm2->llio ? hm2->llio->name : "?");
    va_list ap;
    va_start(ap, fmt);
    emit(hm2->log, hm2->log_ctx, level, prefix, fmt, ap);
    va_end(ap);
}

void hm2_msg_core(hm2_log_fn log, void *ctx, int level, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    emit(log, ctx, level, "hm2: ", fmt, ap);
    va_end(ap);
}

void hm2_log_printf(hm2_log_fn log, void *ctx, int level, const char *fmt, ...)
{
    if (!log)
        return;
    char line[1024]; /* long enough for a path and the reason (dlerror) */
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof(line), fmt, ap);
    va_end(ap);
    log(ctx, level, line);
}
