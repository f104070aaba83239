/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_session.h - libhal's private API for HAL tools (halcmd, rtapi_app's
 * client side, halrun through halcmd): the session as a whole - its name,
 * access, liveness, cleanup - and the few changes halcmd makes that no
 * component may (component ids, simulated time).  No shared-memory layout
 * here: tools read and change HAL objects through hal.h and hal_query.h.
 */
#ifndef HM_HAL_SESSION_H
#define HM_HAL_SESSION_H

#include <stddef.h>
#include <sys/types.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Attach to (creating if needed) this session's segment.  0 or -errno. */
int hal_priv_attach(void);
/* Unmap the segment (after hal_priv_session_release). */
void hal_priv_detach(void);
/* Segment name of the session (depends on HAL_INSTANCE and HAL_OWNER). */
const char *hal_priv_shm_name(void);
const char *hal_priv_instance(void);
/* The session's owner (HAL_OWNER or our uid) and HAL_GROUP's gid (-1
 * unset, -2 no such group). */
uid_t hal_priv_owner_uid(void);
long hal_priv_group_gid(void);
/* Give fd mode 0600, or 0660 and group gid when gid >= 0. */
int hal_priv_set_access(int fd, long gid, const char *what);
/* Abstract unix-socket name of the session's rtapi_app. */
void hal_priv_socket_name(char *buf, size_t len);

enum {
    HAL_SESSION_NONE = 0,    /* no segment */
    HAL_SESSION_RUNNING = 1, /* rtapi_app or a user component lives */
    HAL_SESSION_STALE = 2,   /* left by a crash: a process died inside it */
    HAL_SESSION_IDLE = 3,    /* no process, no crash (signals made by halcmd) */
};
int hal_priv_session_state(void);
/* 1 when the process exists and is not a zombie. */
int hal_priv_pid_alive(int pid);
/* Our start time as rtapi_app records it. */
unsigned long long hal_priv_self_start_time(void);
/* pid of the session's live rtapi_app (0: none), without attaching. */
int hal_priv_session_rtapi_pid(void);
/* 1 when realtime components are listed but their rtapi_app is gone
 * (killed, crashed); *pid gets its last pid.  Needs the segment attached. */
int hal_priv_rt_lost(int *pid);
/* Terminate the session's rtapi_app and user components (halrun -U). */
void hal_priv_session_kill(void);
/* Remove the session's segment, rtapi shmem blocks and log (halrun -U,
 * end of halrun). */
int hal_priv_session_destroy(void);
/* Called by a halcmd leaving the session: when nothing is left in it (no
 * component, process, signal, thread or lock), remove it and detach.
 * Returns 1 when removed. */
int hal_priv_session_release(void);
/* The private runtime directory ($XDG_RUNTIME_DIR/hm2hal or
 * /tmp/hm2hal-UID, mode 0700, checked: ours, not a link), created when
 * `create`.  0 or -errno. */
int hal_priv_runtime_dir(char *buf, size_t len, int create);
/* Open (create, append) rtapi_app's log in the runtime directory, safely;
 * fd or -errno; the path is stored in `path`. */
int hal_priv_open_log(char *path, size_t len);

/* Release the mutex whoever holds it (halcmd -R, crash recovery). */
void hal_priv_force_unlock(void);

/* Remove a component and everything it owns (mutex NOT held). */
int halpr_comp_delete(int comp_id);
/* Component ids for halcmd's LinuxCNC-compatible sequence: reserve n ids
 * (returns the first), give them back if nothing took one since, and
 * renumber a component (the list stays newest first).  Mutex NOT held. */
int halpr_reserve_ids(int n);
void halpr_release_ids(int first, int n);
int halpr_comp_set_id(int old_id, int new_id);
/* halcmd's setexact_for_test_suite_only: -EBUSY once a thread exists. */
int halpr_set_exact(void);
/* Advance the simulated clock when no rtapi_app runs threads (simrun). */
void halpr_sim_advance(long long ns);

#ifdef __cplusplus
}
#endif

#endif /* HM_HAL_SESSION_H */
