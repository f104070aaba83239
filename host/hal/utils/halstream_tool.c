/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halstream_tool.c - the command line and HAL setup halsampler and
 * halstreamer share (halstream_tool.h); messages as LinuxCNC 2.9's tools.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "halstream_tool.h"

volatile sig_atomic_t hs_stop;

static void on_signal(int sig)
{
    (void)sig;
    hs_stop = 1;
}

static int parse_int(const char *s, long min, long max, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (errno != 0 || end == s || *end != '\0' || v < min || v > max)
        return -1;
    *out = v;
    return 0;
}

/* One option with a value; 0 or 1 (error printed). */
static int option_value(hs_tool_t *t, char opt, const char *val)
{
    if (opt == 'c' && parse_int(val, 0, HALSTREAM_MAX_CHAN - 1, &t->chan) != 0) {
        fprintf(stderr, "ERROR: invalid channel number '%s'\n", val);
        return 1;
    }
    if (opt == 'n' && parse_int(val, 0, 0x7fffffffL, &t->count) != 0) {
        fprintf(stderr, "ERROR: invalid sample count '%s'\n", val);
        return 1;
    }
    if (opt == 'N') {
        if (val[0] == '\0' || strlen(val) > HAL_NAME_LEN) {
            fprintf(stderr, "ERROR: invalid component name '%s' (1 to %d characters)\n", val,
                    HAL_NAME_LEN);
            return 1;
        }
        t->name = val;
    }
    return 0;
}

int hs_tool_args(hs_tool_t *t, const char *tool, const char *kind, int argc, char **argv,
                 int sampler)
{
    memset(t, 0, sizeof(*t));
    t->tool = tool;
    t->kind = kind;
    t->count = -1;
    t->comp_id = -1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || a[1] == '\0') {
            if (t->filename != NULL) {
                fprintf(stderr, "ERROR: At most one filename may be specified\n");
                return 1;
            }
            t->filename = a;
            continue;
        }
        char opt = a[1];
        if (sampler && opt == 't' && a[2] == '\0') {
            t->tag = 1;
            continue;
        }
        if (opt != 'c' && opt != 'N' && !(sampler && opt == 'n')) {
            fprintf(stderr, "ERROR: unknown option '%s'\n", a + 1);
            return 1;
        }
        const char *val;
        if (a[2] != '\0')
            val = a + 2;
        else if (i + 1 < argc)
            val = argv[++i];
        else {
            fprintf(stderr, "ERROR: option '%c' needs a value\n", opt);
            return 1;
        }
        if (option_value(t, opt, val) != 0)
            return 1;
    }
    return 0;
}

int hs_tool_start(hs_tool_t *t)
{
    if (t->name == NULL) {
        snprintf(t->compname, sizeof(t->compname), "%s%d", t->tool, (int)getpid());
        t->name = t->compname;
    }
    t->comp_id = hal_init(t->name);
    if (t->comp_id < 0) {
        fprintf(stderr, "ERROR: hal_init() failed: %d\n", t->comp_id);
        return 1;
    }
    char err[256];
    if (halstream_attach(&t->fifo, t->kind, (int)t->chan, err, sizeof(err)) < 0) {
        fprintf(stderr, "%s: ERROR: hal_stream_attach: %s\n", t->tool, err);
        hal_exit(t->comp_id);
        t->comp_id = -1;
        return 1;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    hal_ready(t->comp_id);
    return 0;
}

void hs_tool_end(hs_tool_t *t)
{
    if (t->comp_id < 0)
        return;
    halstream_detach(&t->fifo);
    hal_exit(t->comp_id);
    t->comp_id = -1;
}

long hs_tool_poll_ns(void) { return rtapi_is_simclock() ? 50000 : 1000000; }

void hs_nap(long ns)
{
    struct timespec ts = {0, ns};
    nanosleep(&ts, NULL);
}
