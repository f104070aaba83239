/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_priv.h - the layout of the HAL shared-memory segment and the internal
 * interface between libhal, rtapi_app and halcmd.  Not for components.
 *
 * (Tools such as halcmd use only hal_session.h and hal_query.h, never this
 * layout.)  The segment starts with a hal_hdr_t.  Everything inside is linked by
 * offsets from the segment base (hal_off_t, 0 = none), because every process
 * maps the segment at a different address.  Objects (components, pins,
 * parameters, signals, functions, threads, ...) are carved from the bottom
 * and recycled through per-kind free lists; hal_malloc() memory is carved
 * from the top and never freed.  One robust process-shared mutex guards all
 * of it; the realtime dispatch path never takes it (see rtapi_app.c).
 */
#ifndef HM_HAL_PRIV_H
#define HM_HAL_PRIV_H

#include <pthread.h>
#include <stdint.h>
#include <sys/types.h>

#include "hal.h"
#include "hal_session.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef uint32_t hal_off_t;

#define HAL_SHM_MAGIC 0x484d4832u /* "HMH2" */
#define HAL_SHM_VERSION 5u
#define HAL_HASH_SIZE 4096u /* buckets per name index (power of 2) */
#define HAL_DEFAULT_SHM_SIZE (8u * 1024u * 1024u)
#define HAL_ARGS_LEN 256

typedef enum { HAL_COMP_USER = 0, HAL_COMP_RT = 1 } hal_comp_type_t;

typedef struct {
    hal_off_t next;
    hal_off_t hnext; /* next in the name index bucket */
    int id;
    int type;  /* hal_comp_type_t */
    int ready; /* 0 initializing, 1 ready */
    int pid;   /* user components only */
    uint64_t shmem_base; /* where the owner process maps the segment */
    hal_off_t insmod_args; /* string with the loadrt arguments, or 0 */
    int loaded_by_loadrt;
    char name[HAL_NAME_LEN + 1];
} hal_comp_t;

typedef struct {
    hal_off_t next;
    char name[HAL_NAME_LEN + 1];
} hal_oldname_t;

typedef struct {
    hal_off_t next;
    hal_off_t hnext; /* next in the name index bucket */
    hal_off_t data_ptr_addr; /* the owner's pointer variable (in shm) */
    hal_off_t owner;         /* hal_comp_t */
    hal_off_t signal;        /* hal_sig_t or 0 */
    hal_off_t oldname;       /* hal_oldname_t when aliased */
    int type;
    int dir;
    hal_data_u dummysig; /* storage while unlinked */
    char name[HAL_NAME_LEN + 1];
} hal_pin_t;

typedef struct {
    hal_off_t next;
    hal_off_t hnext; /* next in the name index bucket */
    hal_off_t data_ptr; /* hal_data_u storage (hal_malloc'd) */
    int type;
    int readers;
    int writers;
    int bidirs;
    char name[HAL_NAME_LEN + 1];
} hal_sig_t;

typedef struct {
    hal_off_t next;
    hal_off_t hnext; /* next in the name index bucket */
    hal_off_t data_ptr; /* the owner's variable */
    hal_off_t owner;
    hal_off_t oldname;
    int type;
    int dir;
    char name[HAL_NAME_LEN + 1];
} hal_param_t;

typedef struct {
    hal_off_t next;
    hal_off_t hnext; /* next in the name index bucket */
    hal_off_t owner;
    int uses_fp;
    int reentrant;
    int users;
    uint64_t funct; /* valid in rtapi_app only */
    uint64_t arg;
    hal_off_t runtime;   /* offset of the hal_s32_t* of the NAME.time pin */
    hal_off_t maxtime;   /* hal_s32_t NAME.tmax parameter storage */
    hal_off_t maxtime_increased; /* hal_bit_t NAME.tmax-increased storage */
    char name[HAL_NAME_LEN + 1];
} hal_funct_t;

typedef struct {
    hal_off_t next;
    hal_off_t funct;
} hal_funct_entry_t;

/* Timing storage of a function (hal_malloc'd): the owner's pointer of its
 * NAME.time pin, then NAME.tmax and NAME.tmax-increased. */
typedef struct {
    hal_s32_t *runtime;
    hal_s32_t maxtime;
    hal_bit_t maxtime_increased;
} hal_funct_store_t;

typedef struct {
    hal_off_t next;
    hal_off_t hnext; /* next in the name index bucket */
    int uses_fp;
    int comp_id;
    long period;
    int priority;
    hal_off_t funct_list; /* hal_funct_entry_t, in execution order */
    volatile uint32_t gen; /* bumped on every change of funct_list */
    hal_off_t runtime;     /* offset of hal_s32_t* of the NAME.time pin */
    hal_off_t maxtime;     /* hal_s32_t NAME.tmax storage */
    char name[HAL_NAME_LEN + 1];
} hal_thread_t;

typedef struct {
    uint32_t magic;
    uint32_t version;
    uint32_t size;
    uint32_t hdr_size;
    pthread_mutex_t mutex;
    uint32_t bot; /* objects grow up from here */
    uint32_t top; /* hal_malloc grows down from here */
    int next_id;
    int halcmd_loadrt_count; /* for LinuxCNC-compatible component ids */
    unsigned char lock;
    volatile int threads_running;
    int simclock;
    volatile int64_t sim_time;
    volatile uint32_t sim_abort; /* bumped when waiting functions must give up */
    int rtapi_pid;
    unsigned long long rtapi_start; /* its start time (/proc/PID/stat), against pid reuse */
    uint32_t owner_uid; /* the user the session belongs to */
    int32_t group_gid;  /* HAL_GROUP given at creation, or -1 */
    volatile int msg_level;
    int exact_for_test;
    long clock_period; /* period of the first thread */
    int next_priority;
    hal_off_t comp_list, pin_list, param_list, sig_list, funct_list, thread_list;
    hal_off_t comp_free, pin_free, param_free, sig_free, funct_free, thread_free;
    hal_off_t funct_entry_free, oldname_free;
    /* name indexes: offsets of HAL_HASH_SIZE-bucket arrays, and the last
     * object inserted in each sorted list (insertion hint) */
    hal_off_t idx[6];
    hal_off_t hint[6];
    int active_comps, active_pins, active_params, active_aliases, active_sigs,
        active_functs, active_threads;
    int recycled_comps, recycled_pins, recycled_params, recycled_aliases, recycled_sigs,
        recycled_functs, recycled_threads;
} hal_hdr_t;

enum { HAL_IDX_COMP, HAL_IDX_PIN, HAL_IDX_PARAM, HAL_IDX_SIG, HAL_IDX_FUNCT, HAL_IDX_THREAD };

/* ---- per-process view ---------------------------------------------------- */

extern char *hal_shmem_base;
extern hal_hdr_t *hal_hdr;

#define SHMPTR(off) ((void *)(hal_shmem_base + (off)))
#define SHMOFF(ptr) ((hal_off_t)((char *)(ptr)-hal_shmem_base))
#define SHMCHK(ptr)                                                                  \
    (hal_shmem_base != NULL && (char *)(ptr) > hal_shmem_base + hal_hdr->hdr_size && \
     (char *)(ptr) < hal_shmem_base + hal_hdr->size)

void hal_priv_lock(void);
void hal_priv_unlock(void);

/* Marks this process as rtapi_app: components become realtime. */
void hal_priv_set_realtime_host(int yes);
int hal_priv_is_realtime_host(void);

/* rtapi_app's hooks for thread creation/deletion and the realtime flag. */
typedef struct {
    int (*thread_created)(hal_thread_t *thread); /* called with the mutex held */
    void (*thread_deleting)(hal_thread_t *thread); /* mutex NOT held */
} hal_thread_hooks_t;
void hal_priv_set_thread_hooks(const hal_thread_hooks_t *hooks);
void rtapi_priv_set_in_realtime(int yes);
/* The simulated-clock scheduler marks the start of each period so
 * rtapi_sim_yield() can tell an abort that happened since. */
void rtapi_priv_sim_cycle_begin(void);

/* Messages go through this hook when set (rtapi_app captures the messages
 * of a request to send them to the halcmd that asked). */
typedef void (*rtapi_msg_hook_t)(int level, const char *text);
void rtapi_priv_set_msg_hook(rtapi_msg_hook_t hook);

/* Lookups; the caller holds the mutex. */
hal_comp_t *halpr_find_comp_by_name(const char *name);
hal_comp_t *halpr_find_comp_by_id(int id);
hal_pin_t *halpr_find_pin_by_name(const char *name);
hal_param_t *halpr_find_param_by_name(const char *name);
hal_sig_t *halpr_find_sig_by_name(const char *name);
hal_funct_t *halpr_find_funct_by_name(const char *name);
hal_thread_t *halpr_find_thread_by_name(const char *name);
/* Address of a pin's current value (its signal's storage or its dummy). */
hal_data_u *halpr_pin_value(hal_pin_t *pin);
void *halpr_param_value(hal_param_t *param);
hal_data_u *halpr_sig_value(hal_sig_t *sig);
/* Next component id (caller holds the mutex). */
int halpr_next_id(void);
/* hal_link's checks against given writer/bidir counts (halcmd net dry run). */
int halpr_check_link(hal_pin_t *pin, hal_sig_t *sig, int writers, int bidirs, int quiet);
/* Record the loadrt arguments on the component named `name`. */
int halpr_set_insmod_args(const char *name, const char *args);

#ifdef __cplusplus
}
#endif

#endif /* HM_HAL_PRIV_H */
