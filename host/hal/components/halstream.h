/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halstream.h - the shared-memory FIFO between a realtime sampler/streamer
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
#ifndef HALSTREAM_H
#define HALSTREAM_H

#include <stddef.h>
#include <stdint.h>

#include "hal.h"

#define HALSTREAM_MAX_PINS 21 /* LinuxCNC 2.9's limit ("more than 21 items") */
#define HALSTREAM_MAX_CHAN 8  /* channels per module, as 2.9 */

typedef union {
    double f;
    rtapi_s32 s;
    rtapi_u32 u;
    rtapi_s64 ls;
    rtapi_u64 lu;
    unsigned char b;
} halstream_value_t;

typedef struct halstream_shm halstream_shm_t;

typedef struct {
    halstream_shm_t *shm;
    size_t map_size;
    int owner; /* 1: the realtime side that created it */
    int depth;
    int npins;
    char name[96];
} halstream_t;

/* Parse a cfg string ("bfsu", case-insensitive; also l = s64, k = u64).
 * Returns the number of pins (1..HALSTREAM_MAX_PINS) and fills types[], or
 * -EINVAL with a reason in err. */
int halstream_parse_cfg(const char *cfg, hal_type_t *types, char *err, size_t errlen);
char halstream_type_char(hal_type_t t);

/* The shm object name for channel `chan` of `kind` ("sampler"/"streamer"). */
void halstream_shm_name(char *buf, size_t len, const char *kind, int chan);

/* Realtime side. */
int halstream_create(halstream_t *s, const char *kind, int chan, int depth, int npins,
                     const hal_type_t *types, char *err, size_t errlen);
void halstream_destroy(halstream_t *s);

/* Peer side: open and claim.  Returns 0, or -errno with the reason in err
 * (-ENOENT no such channel, -EBUSY another live peer, -EPROTO bad object). */
int halstream_attach(halstream_t *s, const char *kind, int chan, char *err, size_t errlen);
void halstream_detach(halstream_t *s);

/* Both sides. */
int halstream_pin_count(const halstream_t *s);
hal_type_t halstream_pin_type(const halstream_t *s, int i);
int halstream_capacity(const halstream_t *s);
int halstream_fill(const halstream_t *s);      /* records waiting */
int halstream_closed(const halstream_t *s);    /* realtime side went away */
/* 1 when a live peer is attached (clears a dead peer's claim). */
int halstream_peer_attached(halstream_t *s);

/* Producer: returns 0, or -ENOSPC when full (nothing written). */
int halstream_write(halstream_t *s, const halstream_value_t *vals, rtapi_u32 sampleno);
/* Consumer: returns 0, or -EAGAIN when empty. */
int halstream_read(halstream_t *s, halstream_value_t *vals, rtapi_u32 *sampleno);

/* ---- the realtime modules' side (halstream_module.c) ---- */

/* Check sampler/streamer's cfg= and depth= module parameters (max_chan
 * entries each) before anything is created: at least one cfg string, no
 * gaps, a positive depth for each, no depth without a cfg, every cfg
 * valid.  Fills types[n] and npins[n]; returns the number of channels, or
 * -EINVAL after printing "WHO: ERROR: ..." (who: "SAMPLER", "STREAMER"). */
int halstream_check_params(const char *who, char *const *cfg, const int *depth, int max_chan,
                           hal_type_t (*types)[HALSTREAM_MAX_PINS], int *npins);
/* A HAL pin's value (pin points at the hal_xxx_t storage) to a record
 * value and back. */
void halstream_from_pin(hal_type_t type, const void *pin, halstream_value_t *v);
void halstream_to_pin(hal_type_t type, void *pin, const halstream_value_t *v);
/* Under the simulated clock: wait, with virtual time standing still, until
 * the FIFO has room (want_space) or a record (!want_space).  Returns 1 when
 * it does, 0 when there is no live peer to wait for or the wait must end
 * (threads stopping, module unloading). */
int halstream_wait_peer(halstream_t *s, int want_space);

/* What a sampler and a streamer channel have alike: NAME.N.enable (bit IN,
 * TRUE at load), NAME.N.curr-depth (s32 OUT), the data pins NAME.N.pin.M
 * and the FIFO.  The first member of each module's channel struct (which
 * lives in HAL memory). */
typedef struct {
    hal_bit_t *enable;
    hal_s32_t *curr_depth;
    int npins;
    hal_type_t types[HALSTREAM_MAX_PINS];
    void *pins[HALSTREAM_MAX_PINS];
    halstream_t fifo;
} halstream_chan_t;

/* What sets sampler and streamer apart; the load and unload sequence is
 * halstream_module_load/unload. */
typedef struct {
    const char *name;      /* "sampler": component, HAL names, FIFO kind */
    const char *who;       /* "SAMPLER": messages */
    hal_pin_dir_t pin_dir; /* of the data pins NAME.N.pin.M */
    size_t chan_size;      /* the module's channel struct */
    /* export channel n's own pins (after enable and curr-depth) and set
     * their start values.  0 or a HAL error. */
    int (*export_pins)(void *chan, int comp_id, int n);
    void (*funct)(void *chan, long period); /* exported as NAME.N */
} halstream_module_desc_t;

/* The module's state between load and unload. */
typedef struct {
    int comp_id;
    halstream_chan_t *chans[HALSTREAM_MAX_CHAN];
} halstream_module_t;

/* rtapi_app_main: check cfg=/depth= (HALSTREAM_MAX_CHAN entries each),
 * hal_init, per channel: the struct in HAL memory, its pins, the FIFO, the
 * function; hal_ready.  0, or -errno after printing why with nothing left
 * behind. */
int halstream_module_load(halstream_module_t *m, const halstream_module_desc_t *d,
                          char *const *cfg, const int *depth);
/* rtapi_app_exit: remove the FIFOs, hal_exit. */
void halstream_module_unload(halstream_module_t *m);

/* The module parameters (depth=, cfg=, as LinuxCNC 2.9's) and the entry
 * points of a sampler/streamer module described by DESC, in the module's
 * own file (rtapi_app finds them there). */
#define HALSTREAM_MODULE(DESC)                                                                   \
    static int depth[HALSTREAM_MAX_CHAN];                                                       \
    RTAPI_MP_ARRAY_INT(depth, HALSTREAM_MAX_CHAN, "fifo depth (samples) of each channel");      \
    static char *cfg[HALSTREAM_MAX_CHAN];                                                       \
    RTAPI_MP_ARRAY_STRING(cfg, HALSTREAM_MAX_CHAN, "config string of each channel (b f s u)");  \
    static halstream_module_t halstream_module_;                                                \
    int rtapi_app_main(void)                                                                    \
    {                                                                                           \
        return halstream_module_load(&halstream_module_, &(DESC), cfg, depth);                  \
    }                                                                                           \
    void rtapi_app_exit(void)                                                                   \
    {                                                                                           \
        halstream_module_unload(&halstream_module_);                                            \
    }

#endif /* HALSTREAM_H */
