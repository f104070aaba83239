/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_query.h - introspect and modify HAL by name, from any process of the
 * session.  This is the layer halcmd is built on, and what the Python `hal`
 * module, halsampler/halstreamer, halmeter etc. use.  See docs/hal.md.
 *
 * All functions attach to the session's segment on demand (no component is
 * needed), take the HAL mutex for their duration, and return 0 (or a count)
 * on success and a negative errno value on failure:
 *     -ENOENT  no object of that name
 *     -EINVAL  bad value text / bad argument
 *     -ERANGE  value out of range for the type
 *     -EPERM   not writable (OUT pin, RO parameter, signal with a writer,
 *              pin connected to a signal, HAL locked)
 * Functions taking `err`/`errlen` write a one-line reason (no newline) in
 * LinuxCNC halcmd's wording, e.g. "pin 'and2.0.out' is not writable".
 */
#ifndef HM_HAL_QUERY_H
#define HM_HAL_QUERY_H

#include <stddef.h>

#include "hal.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    HAL_Q_COMP,
    HAL_Q_PIN,
    HAL_Q_PARAM,
    HAL_Q_SIG,
    HAL_Q_FUNCT,
    HAL_Q_THREAD,
    HAL_Q_PIN_ALIAS,   /* aliased pins (name = alias) */
    HAL_Q_PARAM_ALIAS, /* aliased parameters */
} hal_q_kind_t;

typedef struct {
    char name[HAL_NAME_LEN + 1];
    char original[HAL_NAME_LEN + 1]; /* name before an alias, or "" */
    hal_type_t type;
    int dir; /* hal_pin_dir_t for pins, hal_param_dir_t for parameters */
    int owner_id;
    char owner[HAL_NAME_LEN + 1];
    char signal[HAL_NAME_LEN + 1]; /* pins: linked signal or "" */
    hal_data_u value;
} hal_q_pin_t;

typedef struct {
    char name[HAL_NAME_LEN + 1];
    hal_type_t type;
    int readers, writers, bidirs;
    hal_data_u value;
} hal_q_sig_t;

typedef struct {
    char name[HAL_NAME_LEN + 1];
    int id;
    int realtime; /* 1 RT, 0 user */
    int pid;      /* user components */
    int ready;
    char insmod_args[256]; /* loadrt arguments, if loaded by loadrt */
    int loaded_by_loadrt;
} hal_q_comp_t;

typedef struct {
    char name[HAL_NAME_LEN + 1];
    int owner_id;
    char owner[HAL_NAME_LEN + 1];
    int uses_fp, reentrant, users;
    unsigned long long code_addr, arg; /* as seen by rtapi_app */
} hal_q_funct_t;

typedef struct {
    char name[HAL_NAME_LEN + 1];
    long period;
    int uses_fp;
    int comp_id;
    int nfuncts;
    long runtime, maxtime;
} hal_q_thread_t;

/* Attach to this session's segment (HAL_INSTANCE), creating it if needed. */
int hal_q_attach(void);

int hal_q_pin(const char *name, hal_q_pin_t *out);   /* by name or alias */
int hal_q_param(const char *name, hal_q_pin_t *out); /* by name or alias */
int hal_q_sig(const char *name, hal_q_sig_t *out);
int hal_q_comp(const char *name, hal_q_comp_t *out);
int hal_q_funct(const char *name, hal_q_funct_t *out);
int hal_q_thread(const char *name, hal_q_thread_t *out);
/* Function names of a thread in execution order; returns the count (may
 * exceed `max`, then only `max` are stored). */
int hal_q_thread_functs(const char *thread, char (*names)[HAL_NAME_LEN + 1], int max);
/* Pin names linked to a signal, sorted; returns the count. */
int hal_q_sig_pins(const char *sig, char (*names)[HAL_NAME_LEN + 1], int max);

/* Call cb(name, ctx) for every object of `kind` whose name matches
 * `pattern` (NULL or "" = all; a pattern matches a name it is a prefix of,
 * or as an fnmatch(3) glob, as halcmd's show does), in the order halcmd's
 * show lists them.  The names are collected under the lock and cb runs
 * without it, so cb may call any hal_q function.  cb returns nonzero to
 * stop.  Returns the number of names visited. */
typedef int (*hal_q_name_cb)(const char *name, void *ctx);
int hal_q_foreach(hal_q_kind_t kind, const char *pattern, hal_q_name_cb cb, void *ctx);
int hal_q_match(const char *pattern, const char *name);

/* Snapshots: every object of a kind, in the order halcmd's show lists
 * them (components and threads newest first, the others sorted by name),
 * copied under the lock; cb then runs without it, so it may call any hal_q
 * function.  cb returns nonzero to stop.  Returns the number of objects
 * visited, or -errno. */
typedef int (*hal_q_comp_cb)(const hal_q_comp_t *c, void *ctx);
typedef int (*hal_q_pin_cb)(const hal_q_pin_t *p, void *ctx); /* pins and parameters */
typedef int (*hal_q_sig_cb)(const hal_q_sig_t *s, void *ctx);
typedef int (*hal_q_funct_cb)(const hal_q_funct_t *f, void *ctx);
typedef int (*hal_q_thread_cb)(const hal_q_thread_t *t, void *ctx);
int hal_q_each_comp(hal_q_comp_cb cb, void *ctx);
int hal_q_each_pin(hal_q_pin_cb cb, void *ctx);
int hal_q_each_param(hal_q_pin_cb cb, void *ctx);
int hal_q_each_sig(hal_q_sig_cb cb, void *ctx);
int hal_q_each_funct(hal_q_funct_cb cb, void *ctx);
int hal_q_each_thread(hal_q_thread_cb cb, void *ctx);

/* Memory and lock of the session (halcmd's status). */
typedef struct {
    unsigned char lock;
    long shmem_used, shmem_total; /* bytes */
    int active_comps, active_pins, active_params, active_aliases, active_sigs,
        active_functs, active_threads;
    int recycled_comps, recycled_pins, recycled_params, recycled_aliases, recycled_sigs,
        recycled_functs, recycled_threads;
} hal_q_status_t;
int hal_q_status(hal_q_status_t *out);

/* Value text <-> value, with halcmd's rules (bit: 1/0/TRUE/FALSE any case;
 * numbers: C syntax incl. 0x; out-of-range integers are rejected with
 * -ERANGE).  format: getp/gets style ("TRUE", "%.7g", decimal). */
int hal_q_parse_value(hal_type_t type, const char *text, hal_data_u *out);
int hal_q_format_value(hal_type_t type, const hal_data_u *v, char *buf, size_t len);
/* "bit", "float", "s32", "u32", "s64", "u64" -> type, or HAL_TYPE_UNSPECIFIED */
hal_type_t hal_q_type_from_name(const char *name);

/* getp: the value of a pin or parameter as text. */
int hal_q_getp(const char *name, char *buf, size_t len, hal_type_t *type, char *err,
               size_t errlen);
/* setp: set an unlinked IN/IO pin or a RW parameter from text. */
int hal_q_setp(const char *name, const char *value, char *err, size_t errlen);
/* gets/sets on a signal (sets refuses a signal with a writer). */
int hal_q_gets(const char *name, char *buf, size_t len, hal_type_t *type, char *err,
               size_t errlen);
int hal_q_sets(const char *name, const char *value, char *err, size_t errlen);

/* 1 when the pin is linked to a signal that has an OUT or I/O pin. */
int hal_q_pin_has_writer(const char *pin);
/* 1 when the component exists / exists and is ready, 0 otherwise. */
int hal_q_component_exists(const char *name);
int hal_q_component_ready(const char *name);

/* Translate between this process's address of a HAL shared-memory object
 * and a session-wide offset (for peers that exchange locations). */
unsigned long hal_q_shm_offset(const volatile void *ptr);
void *hal_q_shm_ptr(unsigned long offset);

/* Simulated clock (see docs/rtapi.md): 1 when the session runs on it. */
int hal_q_simclock(void);
/* The session's current virtual time (ns); wall-clock sessions: monotonic. */
long long hal_q_time(void);

/* 1 when this session (HAL_INSTANCE) has a segment with a live process,
 * without creating or attaching to it (a viewer started with no HAL
 * running says so instead of creating an empty session). */
int hal_q_session_exists(void);

/* ---- references for lock-free readers ------------------------------------
 * A reference names the value of a pin, parameter or signal in a form that
 * any process of the session can read without the HAL mutex, as a realtime
 * scope must.  hal_q_ref() resolves a name (taking the mutex); the readers
 * below take no lock, make no system call and follow a pin to whatever
 * signal it is linked to at the moment of the read.  A reference whose
 * object is deleted stays safe to read (it reads recycled HAL memory, never
 * outside the segment): re-resolve names after unloads. */
typedef struct {
    unsigned long off; /* session-wide offset of the object */
    int kind;          /* HAL_Q_PIN, HAL_Q_PARAM or HAL_Q_SIG */
    hal_type_t type;
} hal_q_ref_t;

/* kind HAL_Q_PIN, HAL_Q_PARAM or HAL_Q_SIG (pins and parameters also by
 * alias).  -ENOENT: no such object, -EINVAL: bad kind. */
int hal_q_ref(hal_q_kind_t kind, const char *name, hal_q_ref_t *ref);
/* Copy the current values of n references into out[i] (member by the
 * reference's type; the other bytes of out[i] are zero). */
void hal_q_ref_read(const hal_q_ref_t *refs, int n, hal_data_u *out);

#ifdef __cplusplus
}
#endif

#endif /* HM_HAL_QUERY_H */
