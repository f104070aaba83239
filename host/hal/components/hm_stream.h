/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm_stream.h - the shared-memory FIFO between a realtime sampler/streamer
 * channel and its userspace peer (halsampler/halstreamer).
 *
 * One POSIX shared-memory object per channel, named after the HAL session
 * (HAL_INSTANCE, same sanitising as libhal) so sessions never share it:
 *     /hm2hal-<uid>-<instance>.sampler.<chan>   /...streamer.<chan>
 * The realtime module creates it on load and unlinks it on unload (setting
 * `closed` first so an attached peer notices).  It is a single-producer
 * single-consumer ring of `depth` records (capacity exactly `depth`), each
 * record holding one value per pin plus the sample number; `in` and `out`
 * are free-running counters, so in - out is the fill level.
 *
 * A peer claims the channel by storing its pid in `peer_pid` (a second
 * live peer is refused).  Under the simulated clock the realtime side waits
 * for an attached peer instead of overrunning/underrunning (see sampler.c,
 * streamer.c); an unattached or dead peer never blocks it.
 */
#ifndef HM_STREAM_H
#define HM_STREAM_H

#include <stddef.h>
#include <stdint.h>

#include "hal.h"

#define HM_STREAM_MAX_PINS 21 /* LinuxCNC 2.9's limit ("more than 21 items") */
#define HM_STREAM_MAX_CHAN 8  /* channels per module, as 2.9 */

typedef union {
    double f;
    rtapi_s32 s;
    rtapi_u32 u;
    rtapi_s64 ls;
    rtapi_u64 lu;
    unsigned char b;
} hm_stream_value_t;

typedef struct hm_stream_shm hm_stream_shm_t;

typedef struct {
    hm_stream_shm_t *shm;
    size_t map_size;
    int owner; /* 1: the realtime side that created it */
    int depth;
    int npins;
    char name[96];
} hm_stream_t;

/* Parse a cfg string ("bfsu", case-insensitive; also l = s64, k = u64).
 * Returns the number of pins (1..HM_STREAM_MAX_PINS) and fills types[], or
 * -EINVAL with a reason in err. */
int hm_stream_parse_cfg(const char *cfg, hal_type_t *types, char *err, size_t errlen);
char hm_stream_type_char(hal_type_t t);

/* The shm object name for channel `chan` of `kind` ("sampler"/"streamer"). */
void hm_stream_shm_name(char *buf, size_t len, const char *kind, int chan);

/* Realtime side. */
int hm_stream_create(hm_stream_t *s, const char *kind, int chan, int depth, int npins,
                     const hal_type_t *types, char *err, size_t errlen);
void hm_stream_destroy(hm_stream_t *s);

/* Peer side: open and claim.  Returns 0, or -errno with the reason in err
 * (-ENOENT no such channel, -EBUSY another live peer, -EPROTO bad object). */
int hm_stream_attach(hm_stream_t *s, const char *kind, int chan, char *err, size_t errlen);
void hm_stream_detach(hm_stream_t *s);

/* Both sides. */
int hm_stream_pin_count(const hm_stream_t *s);
hal_type_t hm_stream_pin_type(const hm_stream_t *s, int i);
int hm_stream_capacity(const hm_stream_t *s);
int hm_stream_fill(const hm_stream_t *s);      /* records waiting */
int hm_stream_closed(const hm_stream_t *s);    /* realtime side went away */
/* 1 when a live peer is attached (clears a dead peer's claim). */
int hm_stream_peer_attached(hm_stream_t *s);

/* Producer: returns 0, or -ENOSPC when full (nothing written). */
int hm_stream_write(hm_stream_t *s, const hm_stream_value_t *vals, rtapi_u32 sampleno);
/* Consumer: returns 0, or -EAGAIN when empty. */
int hm_stream_read(hm_stream_t *s, hm_stream_value_t *vals, rtapi_u32 *sampleno);

#endif /* HM_STREAM_H */
