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
#include "halstream_tool.h"

#define LINE_MAX_LEN 4096

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
    hs_tool_t t;
    if (hs_tool_args(&t, "halstreamer", "streamer", argc, argv, 0) != 0)
        return 1;
    FILE *in = stdin;
    if (t.filename != NULL) {
        in = fopen(t.filename, "r");
        if (in == NULL) {
            fprintf(stderr, "halstreamer: ERROR: cannot open input file '%s': %s\n", t.filename,
                    strerror(errno));
            return 1;
        }
    }
    if (hs_tool_start(&t) != 0) {
        if (in != stdin)
            fclose(in);
        return 1;
    }
    long poll_ns = hs_tool_poll_ns();
    halstream_value_t vals[HALSTREAM_MAX_PINS];
    char line[LINE_MAX_LEN];
    int lineno = -1;
    int status = 0;
    while (!hs_stop) {
        if (fgets(line, sizeof(line), in) == NULL)
            break;
        lineno++;
        if (line[0] == '#')
            continue;
        int field = 0;
        const char *why = parse_line(line, &t.fifo, vals, &field);
        if (why != NULL) {
            fprintf(stderr, "line %d, field %d: %s, skipping the line\n", lineno, field, why);
            continue;
        }
        while (halstream_write(&t.fifo, vals, 0) != 0) {
            if (hs_stop)
                break;
            if (halstream_closed(&t.fifo)) {
                fprintf(stderr, "halstreamer: ERROR: streamer channel %ld was unloaded\n",
                        t.chan);
                hs_stop = 1;
                break;
            }
            hs_nap(poll_ns);
        }
    }
    if (hs_stop)
        status = 1;
    else if (ferror(in)) {
        fprintf(stderr, "halstreamer: ERROR: reading input failed: %s\n", strerror(errno));
        status = 1;
    }
    if (in != stdin)
        fclose(in);
    hs_tool_end(&t);
    return status;
}
