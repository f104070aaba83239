/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi.h - the realtime API that components are written against.
 *
 * Components are shared objects (lib/rtlib/NAME.so) that rtapi_app loads with
 * dlopen(RTLD_NOW | RTLD_GLOBAL), so a driver module can call functions of a
 * module loaded before it (hm2_pci uses hostmot2's hm2_register), exactly as
 * kernel modules do in LinuxCNC.  A module provides
 *
 *     int  rtapi_app_main(void);   0 on success, -errno on failure
 *     void rtapi_app_exit(void);
 *
 * and declares its module parameters with the RTAPI_MP_* macros below, which
 * rtapi_app finds with dlsym() when it parses `loadrt NAME key=value ...`.
 *
 * Modules are compiled with -fvisibility=hidden and linked with -Bsymbolic,
 * so two modules' private globals never interpose each other.  What a module
 * offers other modules (hostmot2's hm2_register, say) is marked RTAPI_EXPORT,
 * as LinuxCNC marks it EXPORT_SYMBOL.
 *
 * The API is in the spirit of LinuxCNC's rtapi.h (same names, same meaning)
 * so a LinuxCNC component author feels at home; it is not promised to be
 * source compatible beyond what is declared here.
 */
#ifndef HM_RTAPI_H
#define HM_RTAPI_H

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef uint8_t rtapi_u8;
typedef int8_t rtapi_s8;
typedef uint16_t rtapi_u16;
typedef int16_t rtapi_s16;
typedef uint32_t rtapi_u32;
typedef int32_t rtapi_s32;
typedef uint64_t rtapi_u64;
typedef int64_t rtapi_s64;

#define RTAPI_EXPORT __attribute__((visibility("default")))

/* ---- messages ---------------------------------------------------------- */

typedef enum {
    RTAPI_MSG_NONE = 0,
    RTAPI_MSG_ERR,
    RTAPI_MSG_WARN,
    RTAPI_MSG_INFO,
    RTAPI_MSG_DBG,
    RTAPI_MSG_ALL
} msg_level_t;

/* Print when level <= the current message level, settable with
 * rtapi_set_msg_level(), the RTAPI_MSG_LEVEL environment variable, or
 * halcmd's debug command (for the whole session).  Default: RTAPI_MSG_INFO
 * inside rtapi_app (LinuxCNC's uspace rtapi_app shows its modules' INFO
 * messages), RTAPI_MSG_ERR in userspace processes.  Output goes where
 * LinuxCNC's uspace rtapi_app sends it: errors and warnings to the
 * session's stderr, info and debug to its stdout; messages printed while
 * halcmd waits for a request (loadrt, unloadrt) appear on that halcmd's
 * terminal in order with its own lines. */
void rtapi_print_msg(msg_level_t level, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
void rtapi_vprint_msg(msg_level_t level, const char *fmt, va_list ap);
/* Unconditional print (level RTAPI_MSG_NONE is always shown). */
void rtapi_print(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
int rtapi_set_msg_level(int level);
int rtapi_get_msg_level(void);

#define rtapi_snprintf snprintf
#define rtapi_vsnprintf vsnprintf

/* ---- time -------------------------------------------------------------- */

/* Nanoseconds.  On the wall clock: CLOCK_MONOTONIC.  Under the simulated
 * clock (HAL_SIMCLOCK=1, see docs/rtapi.md) the virtual time that threads
 * advance by their period; every process of the session sees the same
 * value because it lives in HAL shared memory. */
long long rtapi_get_time(void);
long long rtapi_get_clocks(void);
/* Busy/short delay; a no-op that only advances nothing under the simulated
 * clock (the simulated world does not move while a function runs). */
void rtapi_delay(long nsec);
long rtapi_delay_max(void);
/* 1 when the session runs on the simulated clock. */
int rtapi_is_simclock(void);
/* 1 inside a realtime thread of rtapi_app, 0 elsewhere. */
int rtapi_is_realtime(void);
/* Under the simulated clock a realtime function may have to wait for a
 * userspace peer (sampler: for halsampler to drain its FIFO; streamer: for
 * halstreamer to fill it) and virtual time must not advance meanwhile, which
 * is what makes a simulated run deterministic.  Such a function loops
 *     while (!peer_ready && !rtapi_sim_yield()) ;
 * rtapi_sim_yield() sleeps briefly and returns nonzero when the function must
 * stop waiting (threads are being stopped, a module is being unloaded, the
 * session is ending).  On the wall clock it returns nonzero at once, so the
 * same code drops/overruns exactly like LinuxCNC there. */
int rtapi_sim_yield(void);

/* ---- shared memory blocks ---------------------------------------------- */
/* Named shared-memory blocks for a realtime module and its userspace peer
 * (sampler/halsampler, streamer/halstreamer), as in LinuxCNC: both sides
 * call rtapi_shmem_new() with the same key and size, then
 * rtapi_shmem_getptr().  Blocks are per session (HAL_INSTANCE).  Returns a
 * handle > 0 or -errno.  The block is removed when its last handle in the
 * session is deleted. */
int rtapi_shmem_new(int key, int module_id, unsigned long size);
int rtapi_shmem_getptr(int handle, void **ptr);
int rtapi_shmem_delete(int handle, int module_id);

/* ---- module parameters ------------------------------------------------- */
/*
 * RTAPI_MP_INT(var, "description") declares `var` (an existing variable of
 * the module) as module parameter "var".  The macros export symbols that
 * rtapi_app looks up with dlsym:
 *     rtapi_info_address_<var>   address of the variable
 *     rtapi_info_type_<var>      one of the type strings below
 *     rtapi_info_size_<var>      element count for arrays (absent otherwise)
 *     rtapi_info_description_<var>
 * Arrays are set with comma-separated values (`names=a,b,c`), at most `num`.
 */
#define RTAPI_MP_TYPE_INT "i"
#define RTAPI_MP_TYPE_LONG "l"
#define RTAPI_MP_TYPE_STRING "s"

#define RTAPI_IP_SYMBOL_(x, var) rtapi_info_##x##_##var

#define RTAPI_MP_DECLARE_(var, mptype, descr)                                      \
    RTAPI_EXPORT __attribute__((used)) void *RTAPI_IP_SYMBOL_(address, var) =     \
        (void *)&(var);                                                            \
    RTAPI_EXPORT __attribute__((used)) const char *RTAPI_IP_SYMBOL_(type, var) = mptype; \
    RTAPI_EXPORT __attribute__((used)) const char *RTAPI_IP_SYMBOL_(description, var) = descr

#define RTAPI_MP_ARRAY_DECLARE_(var, mptype, num, descr) \
    RTAPI_MP_DECLARE_(var, mptype, descr);                \
    RTAPI_EXPORT __attribute__((used)) int RTAPI_IP_SYMBOL_(size, var) = (num)

#define RTAPI_MP_INT(var, descr) RTAPI_MP_DECLARE_(var, RTAPI_MP_TYPE_INT, descr)
#define RTAPI_MP_LONG(var, descr) RTAPI_MP_DECLARE_(var, RTAPI_MP_TYPE_LONG, descr)
#define RTAPI_MP_STRING(var, descr) RTAPI_MP_DECLARE_(var, RTAPI_MP_TYPE_STRING, descr)
#define RTAPI_MP_ARRAY_INT(var, num, descr) \
    RTAPI_MP_ARRAY_DECLARE_(var, RTAPI_MP_TYPE_INT, num, descr)
#define RTAPI_MP_ARRAY_LONG(var, num, descr) \
    RTAPI_MP_ARRAY_DECLARE_(var, RTAPI_MP_TYPE_LONG, num, descr)
#define RTAPI_MP_ARRAY_STRING(var, num, descr) \
    RTAPI_MP_ARRAY_DECLARE_(var, RTAPI_MP_TYPE_STRING, num, descr)

#define MODULE_LICENSE(x) \
    RTAPI_EXPORT __attribute__((used)) const char *rtapi_module_license = (x)
#define MODULE_AUTHOR(x) \
    RTAPI_EXPORT __attribute__((used)) const char *rtapi_module_author = (x)
#define MODULE_DESCRIPTION(x) \
    RTAPI_EXPORT __attribute__((used)) const char *rtapi_module_description = (x)

/* Provided by each module (declared with default visibility here, so the
 * definitions in a -fvisibility=hidden module are still found by dlsym). */
RTAPI_EXPORT int rtapi_app_main(void);
RTAPI_EXPORT void rtapi_app_exit(void);

#ifdef __cplusplus
}
#endif

#endif /* HM_RTAPI_H */
