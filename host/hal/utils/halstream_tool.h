/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halstream_tool.h - what halsampler and halstreamer share: their command
 * line (-c CHAN, -N NAME, one FILENAME; halsampler also -n COUNT and -t),
 * their HAL component and the attachment to the channel's FIFO.
 */
#ifndef HM_HALSTREAM_TOOL_H
#define HM_HALSTREAM_TOOL_H

#include <signal.h>

#include "hal.h"
#include "halstream.h"

typedef struct {
    const char *tool; /* "halsampler" */
    const char *kind; /* "sampler" */
    long chan;
    long count; /* -n (halsampler), -1 = until killed */
    int tag;    /* -t (halsampler) */
    const char *filename, *name;
    char compname[HAL_NAME_LEN + 1];
    int comp_id;
    halstream_t fifo;
} hs_tool_t;

/* Set by SIGINT/SIGTERM once hs_tool_start has run. */
extern volatile sig_atomic_t hs_stop;

/* Parse the command line (sampler: also -n and -t).  0, or 1 after an
 * error message (the tool's exit status). */
int hs_tool_args(hs_tool_t *t, const char *tool, const char *kind, int argc, char **argv,
                 int sampler);
/* Make the component (NAME or TOOL<pid>), attach the FIFO, catch
 * SIGINT/SIGTERM, become ready.  0, or 1 after an error message. */
int hs_tool_start(hs_tool_t *t);
void hs_tool_end(hs_tool_t *t);
/* How long to wait when the FIFO is empty/full: short under the simulated
 * clock, where the realtime side waits for us; 1 ms on the wall clock. */
long hs_tool_poll_ns(void);
void hs_nap(long ns);

#endif /* HM_HALSTREAM_TOOL_H */
