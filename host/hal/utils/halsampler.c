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
#include "halstream.h"

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

static void nap(long ns)
{
    struct timespec ts = {0, ns};
    nanosleep(&ts, NULL);
}

int main(int argc, char **argv)
{
    long chan = 0, count = -1;
    int tag = 0;
    const char *filename = NULL, *name = NULL;
    char err[256], compname[HAL_NAME_LEN + 1];

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] == '-' && a[1] != '\0') {
            char opt = a[1];
            const char *val = NULL;
            if (opt == 'c' || opt == 'n' || opt == 'N') {
                if (a[2] != '\0')
                    val = a + 2;
                else if (i + 1 < argc)
                    val = argv[++i];
                else {
                    fprintf(stderr, "ERROR: option '%c' needs a value\n", opt);
                    return 1;
                }
            } else if (opt == 't' && a[2] == '\0') {
                tag = 1;
                continue;
            } else {
                fprintf(stderr, "ERROR: unknown option '%s'\n", a + 1);
                return 1;
            }
            if (opt == 'c' && parse_int(val, 0, HALSTREAM_MAX_CHAN - 1, &chan) != 0) {
                fprintf(stderr, "ERROR: invalid channel number '%s'\n", val);
                return 1;
            }
            if (opt == 'n' && parse_int(val, 0, 0x7fffffffL, &count) != 0) {
                fprintf(stderr, "ERROR: invalid sample count '%s'\n", val);
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
    if (count == 0)
        return 0;

    FILE *out = stdout;
    if (filename != NULL) {
        out = fopen(filename, "w");
        if (out == NULL) {
            fprintf(stderr, "halsampler: ERROR: cannot open output file '%s': %s\n", filename,
                    strerror(errno));
            return 1;
        }
    }
    if (name == NULL) {
        snprintf(compname, sizeof(compname), "halsampler%d", (int)getpid());
        name = compname;
    }
    int comp_id = hal_init(name);
    if (comp_id < 0) {
        fprintf(stderr, "ERROR: hal_init() failed: %d\n", comp_id);
        return 1;
    }
    halstream_t fifo;
    int r = halstream_attach(&fifo, "sampler", (int)chan, err, sizeof(err));
    if (r < 0) {
        fprintf(stderr, "halsampler: ERROR: hal_stream_attach: %s\n", err);
        hal_exit(comp_id);
        return 1;
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    hal_ready(comp_id);

    /* Poll: fast under the simulated clock, where the realtime side waits
     * for us; 1 ms on the wall clock. */
    long poll_ns = rtapi_is_simclock() ? 50000 : 1000000;
    int npins = halstream_pin_count(&fifo);
    halstream_value_t vals[HALSTREAM_MAX_PINS];
    rtapi_u32 expected = 0;
    int status = 1;
    while (!stop_requested) {
        rtapi_u32 num;
        if (halstream_read(&fifo, vals, &num) != 0) {
            if (halstream_closed(&fifo)) {
                fprintf(stderr, "halsampler: ERROR: sampler channel %ld was unloaded\n", chan);
                break;
            }
            fflush(out);
            nap(poll_ns);
            continue;
        }
        if (num != expected)
            fputs("overrun\n", out);
        expected = num + 1;
        if (tag)
            fprintf(out, "%lu ", (unsigned long)num);
        for (int i = 0; i < npins; i++)
            print_value(out, halstream_pin_type(&fifo, i), &vals[i]);
        fputc('\n', out);
        if (count > 0 && --count == 0) {
            status = 0;
            break;
        }
    }
    halstream_detach(&fifo);
    if (fflush(out) != 0 || ferror(out)) {
        fprintf(stderr, "halsampler: ERROR: writing output failed: %s\n", strerror(errno));
        status = 1;
    }
    if (out != stdout)
        fclose(out);
    hal_exit(comp_id);
    return status;
}
