/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halview.h - the C helper under halmeter, halscope, halshow and halweb
 * (tools/halview), loaded by their Python code with ctypes.  A flat API on
 * top of hal_query.h (names, values, halcmd's set rules) and of scope_rt's
 * shared memory (scope_shm.h).  Every function returns 0 or a count on
 * success and a negative errno value on failure; those taking err/errlen
 * write a one-line reason there.
 */
#ifndef HM_HALVIEW_H
#define HM_HALVIEW_H

#include <stddef.h>
#include <stdint.h>

/* object kinds, as hal_q_kind_t */
enum { HV_COMP = 0, HV_PIN = 1, HV_PARAM = 2, HV_SIG = 3, HV_FUNCT = 4, HV_THREAD = 5 };

int hv_attach(void);
/* 1 when the session's HAL segment exists (without creating it). */
int hv_session_exists(void);
int hv_simclock(void);
long long hv_time(void);

/* Names of `kind` matching `pattern` ("" = all) in halcmd's order, each
 * followed by '\n'.  Returns the bytes needed (excluding the NUL); when that
 * is >= len the list was cut: call again with a larger buffer. */
long hv_list(int kind, const char *pattern, char *buf, size_t len);

/* One object as tab-separated fields (no newline); -ENOENT when gone.
 *   pin:    type dir value signal owner
 *   param:  type dir value owner
 *   sig:    type value writers readers bidirs pins(space-separated)
 *   comp:   id rt(0/1) pid ready args
 *   funct:  owner_id uses_fp reentrant users
 *   thread: period uses_fp functs(space-separated in order)
 * Values are formatted as halcmd's getp/gets print them. */
long hv_info(int kind, const char *name, char *buf, size_t len);

/* getp/gets and setp/sets with halcmd's rules and error texts. */
int hv_get(int kind, const char *name, char *buf, size_t len, char *err, size_t errlen);
int hv_set(int kind, const char *name, const char *value, char *err, size_t errlen);

/* Several values at once: names separated by '\n' with a kind each
 * (kinds[i]); values written to buf separated by '\n' ("?" for an object
 * that is gone).  Returns the bytes needed, as hv_list. */
long hv_get_many(int n, const int *kinds, const char *names, char *buf, size_t len);

/* ---- scope_rt ------------------------------------------------------------ */

typedef struct hv_scope hv_scope_t;

typedef struct {
    int64_t state, error, capture_seq, forced, nchan;
    int64_t capacity, widx, trig_idx, start_idx;
    int64_t t_first, t_trig, interval, lost, calls, num_samples, pending, done_calls;
} hv_scope_status_t;

/* Attach to the loaded scope_rt's shared memory (-ENOENT: not loaded). */
hv_scope_t *hv_scope_open(char *err, size_t errlen);
void hv_scope_close(hv_scope_t *h);
int hv_scope_status(hv_scope_t *h, hv_scope_status_t *st);
/* Resolve channel i (0..15) of the next run: a pin, parameter or signal.
 * Returns its hal type. */
int hv_scope_set_chan(hv_scope_t *h, int i, int kind, const char *name, char *err,
                      size_t errlen);
/* Configure and arm (mode: scope_shm.h enum scope_mode). */
int hv_scope_arm(hv_scope_t *h, int nchan, int mult, uint64_t rec_len, uint64_t pretrig,
                 int trig_chan, int edge, double level, int mode, int reader_wait, char *err,
                 size_t errlen);
int hv_scope_stop(hv_scope_t *h);
/* Copy records [first, first+count) of the current run (count*nchan
 * 8-byte values, each member as hal_data_u) into out.  Returns the first
 * index that is certainly intact (records before it may have been
 * overwritten during the copy, roll mode only). */
int64_t hv_scope_read(hv_scope_t *h, uint64_t first, uint64_t count, void *out);
/* Roll mode: records < idx are consumed (the ring may reuse them). */
void hv_scope_consume(hv_scope_t *h, uint64_t idx);

#endif /* HM_HALVIEW_H */
