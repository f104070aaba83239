/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halsampler - copy samples from a sampler(9) FIFO to stdout or a file.
 *
 *   halsampler [-c CHAN] [-n COUNT] [-t] [-N NAME] [FILENAME]
 *
 * One line per sample, each value followed by a space, as LinuxCNC 2.9:
 * bits 0/1, floats "%f", s32/s64 signed, u32/u64 unsigned decimal; -t puts
 * the sample number first.  A gap in the sample numbers (samples the
 * sampler had to drop because the FIFO was full) is marked by a line
 * "overrun".  -n COUNT exits with status 0 after COUNT samples; without it
 * halsampler runs until killed and then exits with status 1.
 *
 * -N NAME (our extension) sets the HAL component name (default
 * halsampler<pid>); the component becomes ready once the FIFO is attached,
 * so `loadusr -Wn NAME halsampler -N NAME ...` returns when no sample can
 * be missed any more.  See docs/halsampler.md.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "hal.h"
#include "halstream_tool.h"

static void print_value(FILE *f, hal_type_t t, const halstream_value_t *v)
{
    switch (t) {
    case HAL_BIT:
        fputs(v->b ? "1 " : "0 ", f);
        break;
    case HAL_FLOAT:
        fprintf(f, "%f ", v->f);
        break;
    case HAL_S32:
        fprintf(f, "%ld ", (long)v->s);
        break;
    case HAL_U32:
        fprintf(f, "%lu ", (unsigned long)v->u);
        break;
    case HAL_S64:
        fprintf(f, "%" PRId64 " ", (int64_t)v->ls);
        break;
    case HAL_U64:
        fprintf(f, "%" PRIu64 " ", (uint64_t)v->lu);
        break;
    default:
        fputs("? ", f);
        break;
    }
}

int main(int argc, char **argv)
{
    hs_tool_t t;
    if (hs_tool_args(&t, "halsampler", "sampler", argc, argv, 1) != 0)
        return 1;
    if (t.count == 0)
        return 0;
    FILE *out = stdout;
    if (t.filename != NULL) {
        out = fopen(t.filename, "w");
        if (out == NULL) {
            fprintf(stderr, "halsampler: ERROR: cannot open output file '%s': %s\n", t.filename,
                    strerror(errno));
            return 1;
        }
    }
    if (hs_tool_start(&t) != 0) {
        if (out != stdout)
            fclose(out);
        return 1;
    }
    long poll_ns = hs_tool_poll_ns();
    int npins = halstream_pin_count(&t.fifo);
    halstream_value_t vals[HALSTREAM_MAX_PINS];
    rtapi_u32 expected = 0;
    long count = t.count;
    int status = 1;
    while (!hs_stop) {
        rtapi_u32 num;
        if (halstream_read(&t.fifo, vals, &num) != 0) {
            if (halstream_closed(&t.fifo)) {
                fprintf(stderr, "halsampler: ERROR: sampler channel %ld was unloaded\n", t.chan);
                break;
            }
            fflush(out);
            hs_nap(poll_ns);
            continue;
        }
        if (num != expected)
            fputs("overrun\n", out);
        expected = num + 1;
        if (t.tag)
            fprintf(out, "%lu ", (unsigned long)num);
        for (int i = 0; i < npins; i++)
            print_value(out, halstream_pin_type(&t.fifo, i), &vals[i]);
        fputc('\n', out);
        if (count > 0 && --count == 0) {
            status = 0;
            break;
        }
    }
    if (fflush(out) != 0 || ferror(out)) {
        fprintf(stderr, "halsampler: ERROR: writing output failed: %s\n", strerror(errno));
        status = 1;
    }
    if (out != stdout)
        fclose(out);
    hs_tool_end(&t);
    return status;
}
