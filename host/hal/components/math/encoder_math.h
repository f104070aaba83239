/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * encoder_math.h - the counter of the encoder component (docs/encoder.md),
 * apart from its HAL pins so it can be unit-tested on its own.  Same
 * arithmetic as LinuxCNC 2.9's software encoder, so the same input samples
 * give the same counts, positions and velocities (tests/hal/encoder-*
 * compare with LinuxCNC's recorded output).
 *
 * update-counters (enc_update) decodes the inputs every fast period: a
 * quadrature step forward (A leads B: 00 10 11 01) counts +1, back -1, a
 * jump of two states (both inputs changed) nothing; x1 counts only the
 * 00 -> 10 step (and back); counter mode counts rising edges of A.  It
 * notes the raw count and a time stamp at each count, the raw count at a
 * rising edge of Z while index-enable is armed, and at the chosen edges of
 * latch-input.
 *
 * capture-position (enc_capture) publishes: counts = raw count at the last
 * count - offset, where the offset is the raw count at the index (and
 * index-enable is cleared) or at a reset; velocity = counts moved / time
 * between their time stamps (after two counts since a stop), shrinking
 * while no count comes, and 0 once the time since the last count is longer
 * than one count at min-speed-estimate; position-interpolated = position +
 * velocity x time since the last count.
 */
#ifndef HM_ENCODER_MATH_H
#define HM_ENCODER_MATH_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>

/* What update-counters hands to capture-position. */
typedef struct {
    bool counted, indexed, latched;
    int32_t raw;         /* raw count at the last count */
    uint32_t stamp;      /* time of the last count (ns, wraps) */
    int32_t index_raw;   /* raw count at the index */
    int32_t latch_raw;   /* raw count at the latch edge */
} enc_events_t;

typedef struct {
    /* update-counters state */
    unsigned char ab;     /* previous A (bit 0) and B (bit 1) */
    bool old_z, old_latch;
    bool index_armed;     /* index-enable seen by capture-position */
    int32_t raw;          /* rawcounts */
    uint32_t timebase;    /* ns, advanced by every update period */
    enc_events_t ev;

    /* capture-position state */
    int32_t last_raw;     /* raw count at the last processed count */
    uint32_t last_stamp;
    int32_t offset;       /* raw count that is counts 0 */
    int32_t latch_raw;
    int moves;            /* counts since velocity was last 0 (0..2) */
    double old_scale, recip; /* position-scale and its reciprocal */

    /* published */
    int32_t counts, counts_latched;
    double position, position_latched, position_interp, velocity;
} enc_t;

static inline void enc_init(enc_t *e)
{
    *e = (enc_t){0};
    e->old_scale = 1.0;
    e->recip = 1.0;
}

/* Count change for a move from inputs `from` to `to` (A | B << 1), indexed
 * [x4][from << 2 | to]: forward (A leads B: 00 10 11 01) +1, back -1, both
 * inputs changed 0; x1 counts only between the 00 and 10 states.  A table,
 * as the change is irregular and a branch on it mispredicted often. */
static const signed char enc_steps[2][16] = {
    {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
    {0, 1, -1, 0, -1, 0, 0, 1, 1, 0, 0, -1, 0, -1, 1, 0},
};

static inline int enc_decode(unsigned from, unsigned to, bool x4)
{
    return enc_steps[x4][(from << 2 | to) & 15];
}

/* One update-counters period. */
static inline void enc_update(enc_t *e, bool a, bool b, bool z, bool latch_in,
                              bool latch_rising, bool latch_falling, bool x4,
                              bool counter_mode, long period_ns)
{
    unsigned ab = (unsigned)a | (unsigned)b << 1;
    int d;
    if (counter_mode)
        d = (a && !(e->ab & 1)) ? 1 : 0;
    else
        d = enc_decode(e->ab, ab, x4);
    e->ab = (unsigned char)ab;
    /* without a branch on d (counts come at irregular periods); ev.raw is
     * raw, which only a count changes */
    e->raw = (int32_t)((uint32_t)e->raw + (uint32_t)d);
    e->ev.raw = e->raw;
    e->ev.stamp = d != 0 ? e->timebase : e->ev.stamp;
    e->ev.counted |= d != 0;
    if (z && !e->old_z && e->index_armed) {
        e->ev.index_raw = e->raw;
        e->ev.indexed = true;
        e->index_armed = false;
    }
    e->old_z = z;
    if ((latch_in && !e->old_latch && latch_rising) ||
        (!latch_in && e->old_latch && latch_falling)) {
        e->ev.latch_raw = e->raw;
        e->ev.latched = true;
    }
    e->old_latch = latch_in;
    e->timebase += (uint32_t)period_ns;
}

/* Velocity while no count comes: the speed of a count arriving now, if
 * lower than the last velocity; 0 once that is below min_speed. */
static inline void enc_no_count(enc_t *e, double min_speed)
{
    if (e->moves == 0) {
        e->velocity = 0.0;
        return;
    }
    double dt = (double)(uint32_t)(e->timebase - e->last_stamp);
    if (dt < 1e9 / (min_speed * e->recip)) {
        double v = e->recip / (dt * 1e-9);
        if (v < 0.0)
            v = -v;
        if (v < e->velocity)
            e->velocity = v;
        if (-v > e->velocity)
            e->velocity = -v;
    } else {
        e->moves = 0;
        e->velocity = 0.0;
    }
}

/* One capture-position period.  *index_enable (I/O) is cleared at an
 * index; *scale and *min_speed are replaced by 1 when (near) zero, as 2.9
 * writes them back to their pins. */
static inline void enc_capture(enc_t *e, bool *index_enable, double *scale, double *min_speed,
                               bool reset)
{
    enc_events_t *ev = &e->ev;
    if (ev->indexed) {
        ev->indexed = false;
        e->offset = ev->index_raw;
        *index_enable = false;
    }
    if (ev->latched) {
        ev->latched = false;
        e->latch_raw = ev->latch_raw;
    }
    e->index_armed = *index_enable;
    if (*scale != e->old_scale) {
        e->old_scale = *scale;
        if (*scale < 1e-20 && *scale > -1e-20)
            *scale = 1.0;
        e->recip = 1.0 / *scale;
    }
    if (*min_speed == 0.0)
        *min_speed = 1.0;
    if (reset) {
        e->offset = e->raw;
        e->last_raw = e->raw;
    }
    if (ev->counted) {
        ev->counted = false;
        int32_t dc = (int32_t)((uint32_t)ev->raw - (uint32_t)e->last_raw);
        double dt = (double)(uint32_t)(ev->stamp - e->last_stamp);
        e->last_raw = ev->raw;
        e->last_stamp = ev->stamp;
        if (e->moves < 2)
            e->moves++;
        else
            e->velocity = (dc * e->recip) / (dt * 1e-9);
    } else {
        enc_no_count(e, *min_speed);
    }
    e->counts = (int32_t)((uint32_t)e->last_raw - (uint32_t)e->offset);
    e->position = e->counts * e->recip;
    double since = (double)(uint32_t)(e->timebase - e->last_stamp);
    e->position_interp = e->position + e->velocity * (since * 1e-9);
    e->counts_latched = (int32_t)((uint32_t)e->latch_raw - (uint32_t)e->offset);
    e->position_latched = e->counts_latched * e->recip;
}

#endif /* HM_ENCODER_MATH_H */
