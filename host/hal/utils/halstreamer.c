/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halstreamer - copy lines of numbers from stdin or a file into a
 * streamer(9) FIFO.
 *
 *   halstreamer [-c CHAN] [-N NAME] [FILENAME]
 *
 * Each line holds one value per streamer pin, separated by whitespace:
 * bits 0 or 1, floats as strtod(3), s32/s64 as strtol(3) base 10, u32/u64
 * as strtoul(3) base 10 (out-of-range integers are truncated to the pin's
 * width, as LinuxCNC 2.9 does).  Lines starting with '#' are comments;
 * extra fields are ignored.  A bad line is reported on stderr as
 *     line L, field F: REASON, skipping the line
 * with L and F counted from 0 (comments count as lines), REASON one of
 * "bit value not 0 or 1", "bad character", "premature end of line" - the
 * text and numbering of 2.9 - and skipped.  When the FIFO is full
 * halstreamer waits.  Exit status 0 at end of input, 1 if killed or on a
 * setup error.
 *
 * -N NAME (our extension) sets the HAL component name (default
 * halstreamer<pid>).  See docs/halstreamer.md.
 */
#define _GNU_SOURCE
#include <ctype.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "hal.h"
#include "halstream.h"

#define LINE_MAX_LEN 4096

static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
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

static void nap(long ns)
{
    struct timespec ts = {0, ns};
    nanosleep(&ts, NULL);
}

/* Parse one line into vals; returns NULL or the reason, with *field set. */
static const char *parse_line(const char *line, const halstream_t *fifo, halstream_value_t *vals,
                              int *field)
{
    const char *cp = line;
    int npins = halstream_pin_count(fifo);
    for (int n = 0; n < npins; n++) {
        char *end = NULL;
        *field = n;
        while (isspace((unsigned char)*cp))
            cp++;
        memset(&vals[n], 0, sizeof(vals[n]));
        switch (halstream_pin_type(fifo, n)) {
        case HAL_BIT:
            if (*cp != '0' && *cp != '1')
                return "bit value not 0 or 1";
            vals[n].b = (unsigned char)(*cp - '0');
            end = (char *)cp + 1;
            break;
        case HAL_FLOAT:
            vals[n].f = strtod(cp, &end);
            break;
        case HAL_S32:
            vals[n].s = (rtapi_s32)strtol(cp, &end, 10);
            break;
        case HAL_U32:
            vals[n].u = (rtapi_u32)strtoul(cp, &end, 10);
            break;
        case HAL_S64:
            vals[n].ls = (rtapi_s64)strtoll(cp, &end, 10);
            break;
        case HAL_U64:
            vals[n].lu = (rtapi_u64)strtoull(cp, &end, 10);
            break;
        default:
            return "unsupported pin type";
        }
        /* a field must end in whitespace (the newline ends the last one) */
        if (*end == '\0')
            return "premature end of line";
        if (!isspace((unsigned char)*end))
            return "bad character";
        cp = end;
    }
    return NULL;
}

int main(int argc, char **argv)
{
    long chan = 0;
    const char *filename = NULL, *name = NULL;
    char err[256], compname[HAL_NAME_LEN + 1];

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] == '-' && a[1] != '\0') {
            char opt = a[1];
            const char *val;
            if (opt != 'c' && opt != 'N') {
                fprintf(stderr, "ERROR: unknown option '%s'\n", a + 1);
                return 1;
            }
            if (a[2] != '\0')
                val = a + 2;
            else if (i + 1 < argc)
                val = argv[++i];
            else {
                fprintf(stderr, "ERROR: option '%c' needs a value\n", opt);
                return 1;
            }
            if (opt == 'c' && parse_int(val, 0, HALSTREAM_MAX_CHAN - 1, &chan) != 0) {
                fprintf(stderr, "ERROR: invalid channel number '%s'\n", val);
                return 1;
            }
            if (opt == 'N') {
                if (val[0] == '\0' || strlen(val) > HAL_NAME_LEN) {
                    fprintf(stderr, "ERROR: invalid component name '%s' (1 to %d characters)\n",
                            val, HAL_NAME_LEN);
                    return 1;
                }
                name = val;
            }
        } else {
            if (filename != NULL) {
                fprintf(stderr, "ERROR: At most one filename may be specified\n");
                return 1;
            }
            filename = a;
        }
    }

    FILE *in = stdin;
    if (filename != NULL) {
        in = fopen(filename, "r");
        if (in == NULL) {
            fprintf(stderr, "halstreamer: ERROR: cannot open input file '%s': %s\n", filename,
                    strerror(errno));
            return 1;
        }
    }
    if (name == NULL) {
        snprintf(compname, sizeof(compname), "halstreamer%d", (int)getpid());
        name = compname;
    }
    int comp_id = hal_init(name);
    if (comp_id < 0) {
        fprintf(stderr, "ERROR: hal_init() failed: %d\n", comp_id);
        return 1;
    }
    halstream_t fifo;
    int r = halstream_attach(&fifo, "streamer", (int)chan, err, sizeof(err));
    if (r < 0) {
        fprintf(stderr, "halstreamer: ERROR: hal_stream_attach: %s\n", err);
        hal_exit(comp_id);
        return 1;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    hal_ready(comp_id);

    long poll_ns = rtapi_is_simclock() ? 50000 : 1000000;
    halstream_value_t vals[HALSTREAM_MAX_PINS];
    char line[LINE_MAX_LEN];
    int lineno = -1;
    int status = 0;
    while (!stop_requested) {
        if (fgets(line, sizeof(line), in) == NULL)
            break;
        lineno++;
        if (line[0] == '#')
            continue;
        int field = 0;
        const char *why = parse_line(line, &fifo, vals, &field);
        if (why != NULL) {
            fprintf(stderr, "line %d, field %d: %s, skipping the line\n", lineno, field, why);
            continue;
        }
        while (halstream_write(&fifo, vals, 0) != 0) {
            if (stop_requested)
                break;
            if (halstream_closed(&fifo)) {
                fprintf(stderr, "halstreamer: ERROR: streamer channel %ld was unloaded\n", chan);
                stop_requested = 1;
                break;
            }
            nap(poll_ns);
        }
    }
    if (stop_requested)
        status = 1;
    else if (ferror(in)) {
        fprintf(stderr, "halstreamer: ERROR: reading input failed: %s\n", strerror(errno));
        status = 1;
    }
    halstream_detach(&fifo);
    if (in != stdin)
        fclose(in);
    hal_exit(comp_id);
    return status;
}
