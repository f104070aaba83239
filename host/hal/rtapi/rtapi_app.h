/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_app.h - the parts of rtapi_app (see rtapi_app.c) and what they
 * offer each other: the HAL threads and the simulated-clock scheduler
 * (rtapi_threads.c), loaded modules (rtapi_modules.c) and the request
 * server on the session socket (rtapi_server.c).
 */
#ifndef HM_RTAPI_APP_H
#define HM_RTAPI_APP_H

#include <signal.h>

#include "hal_priv.h"

/* ---- rtapi_threads.c ---- */
extern const hal_thread_hooks_t rtapi_thread_hooks;
/* Start the scheduler of a simulated-clock session; 0 or -errno. */
int rtapi_threads_init(int simclock);
void rtapi_threads_exit(void);
/* 1 while a HAL thread exists. */
int rtapi_threads_exist(void);
/* Wait until no thread is inside a period begun before now. */
void rtapi_quiesce(void);
/* simrun NS (request from halcmd). */
int rtapi_do_simrun(int argc, char **argv);

/* ---- rtapi_modules.c ---- */
int rtapi_do_load(int argc, char **argv);
int rtapi_do_unload(int argc, char **argv);
void rtapi_unload_all(void);
/* 1 while a module is loaded. */
int rtapi_modules_loaded(void);
/* Names of the loaded modules, one a line, newest first (malloc'd). */
char *rtapi_module_list(void);
int rtapi_parse_long(const char *s, long *out);

/* ---- rtapi_server.c ---- */
/* Capture or print a module's message (the rtapi message hook). */
void rtapi_msg_hook(int level, const char *text);
/* Serve requests until told to quit or nothing is loaded; see rtapi_app.c. */
int rtapi_serve(int lfd);
void rtapi_server_exit(void);

/* ---- rtapi_app.c ---- */
extern volatile sig_atomic_t rtapi_got_signal;

#endif /* HM_RTAPI_APP_H */
