/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * scope_shm.h - the shared memory between the realtime scope (scope_rt,
 * function scope.sample) and its userspace front ends (halscope, halweb).
 *
 * Two rtapi shared-memory blocks of the session:
 *   SCOPE_CTRL_KEY  a scope_ctrl_t: configuration, command handshake, status
 *   SCOPE_DATA_KEY  num_samples value slots (hal_data_u, 8 bytes each)
 *
 * The data block is a ring of records; a record holds one slot per channel,
 * so it holds num_samples / nchan records.  Record r of a run is stored at
 * slot (r mod capacity) * nchan.  `widx` counts the records written since
 * the run was armed and is published (release) after each record.
 *
 * Handshake: the front end makes cfg_gen odd, writes `cfg`, makes cfg_gen
 * even again, then stores `cmd` and bumps `cmd_seq` (release).  At its next
 * call the realtime side sees the new cmd_seq, copies `cfg` and uses the
 * copy only if cfg_gen was even and unchanged around the copy (otherwise it
 * tries again at the following call); then it answers in `ack_seq`.
 *
 * Reading without tearing: a record is complete once widx has passed it.
 * In roll mode the ring is overwritten; a reader copies records, then reads
 * widx again (w2): every record r <= w2 - capacity may have been overwritten
 * meanwhile and is discarded (counted as lost).  A triggered capture is not
 * written to once its state is DONE.
 */
#ifndef HM_SCOPE_SHM_H
#define HM_SCOPE_SHM_H

#include <stdint.h>

#include "hal.h"
#include "hal_query.h"

#define SCOPE_CTRL_KEY 0x5C09E001
#define SCOPE_DATA_KEY 0x5C09E002
#define SCOPE_MAGIC 0x53434f50u /* "SCOP" */
#define SCOPE_VERSION 1u
#define SCOPE_MAX_CHAN 16
#define SCOPE_DEFAULT_SAMPLES 16000

enum scope_mode {
    SCOPE_MODE_NORMAL = 0, /* wait for the trigger; the front end re-arms */
    SCOPE_MODE_AUTO = 1,   /* as normal, but trigger anyway after a record length */
    SCOPE_MODE_SINGLE = 2, /* as normal; the front end does not re-arm */
    SCOPE_MODE_ROLL = 3,   /* sample continuously into the ring */
};

enum scope_state {
    SCOPE_IDLE = 0,
    SCOPE_ARMED = 1,     /* collecting, waiting for the trigger */
    SCOPE_TRIGGERED = 2, /* collecting the samples after the trigger */
    SCOPE_DONE = 3,      /* capture complete: [start, start + rec_len) */
    SCOPE_ROLLING = 4,
    SCOPE_ERROR = 5, /* the last ARM was refused: see `error` */
};

enum scope_edge { SCOPE_RISING = 0, SCOPE_FALLING = 1 };

enum scope_cmd { SCOPE_CMD_NONE = 0, SCOPE_CMD_ARM = 1, SCOPE_CMD_STOP = 2 };

typedef struct {
    int32_t nchan;
    int32_t mult; /* sample every mult-th call */
    hal_q_ref_t chan[SCOPE_MAX_CHAN];
    uint64_t rec_len;  /* records per capture */
    uint64_t pretrig;  /* records before the trigger record */
    int32_t trig_chan; /* -1: trigger at once */
    int32_t trig_edge; /* enum scope_edge */
    double trig_level;
    int32_t mode;        /* enum scope_mode */
    int32_t reader_wait; /* simulated clock: wait for the reader (see scope_rt.c) */
} scope_cfg_t;

typedef struct {
    uint32_t magic;
    uint32_t version;
    uint64_t num_samples; /* slots in the data block, fixed at load */

    /* configuration: written by the front end under the cfg_gen seqlock
     * (odd while writing), copied by the realtime side when it sees a new
     * cmd_seq and an even, unchanged cfg_gen */
    volatile uint32_t cfg_gen;
    scope_cfg_t cfg;

    /* handshake */
    volatile uint32_t cmd;
    volatile uint32_t cmd_seq;
    volatile uint32_t ack_seq;

    /* status (realtime side writes) */
    volatile uint32_t state;
    volatile int32_t error; /* why the last ARM was refused (-errno) */
    volatile uint32_t capture_seq; /* bumped when a capture is DONE */
    volatile uint32_t forced;      /* auto mode: the last trigger was forced */
    volatile uint64_t capacity;    /* records in the ring for this run */
    volatile uint64_t widx;        /* records written since ARM */
    volatile uint64_t trig_idx;    /* record index of the trigger */
    volatile uint64_t start_idx;   /* first record of a DONE capture */
    volatile int64_t t_first;      /* rtapi_get_time() of record 0 */
    volatile int64_t t_trig;       /* rtapi_get_time() of the trigger record */
    volatile int64_t interval;     /* ns between records (mult * period) */
    volatile uint64_t lost;        /* roll: records overwritten unread */
    volatile uint64_t calls;       /* calls of scope.sample (any state) */
    volatile uint64_t done_calls;  /* `calls` when the last capture was DONE */

    /* reader (front end writes) */
    volatile uint64_t rd_idx; /* roll: records < rd_idx have been consumed */
    volatile int32_t reader_pid; /* the reader that asked for reader_wait */
} scope_ctrl_t;

#endif /* HM_SCOPE_SHM_H */
