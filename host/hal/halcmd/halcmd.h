/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd.h - shared state and helpers of halcmd's parts.
 */
#ifndef HM_HALCMD_H
#define HM_HALCMD_H

#include <stdio.h>

#include "hal.h"
#include "hal_priv.h"
#include "hal_query.h"

typedef struct {
    int keep_going;  /* -k */
    int quiet;       /* -q: errors only (default) */
    int very_quiet;  /* -Q: nothing */
    int verbose;     /* -v */
    int very_verbose;/* -V */
    int script;      /* -s: no headers */
    int echo;        /* -e / echo command */
    const char *ini; /* -i */
    const char *filename; /* current file, NULL for command line */
    int linenum;
    int comp_id;     /* halcmd's own component */
    int loadrt_done; /* number of loadrt done by this halcmd */
    int done;        /* quit/exit seen */
    char comp_name[HAL_NAME_LEN + 1];
} halcmd_state_t;

extern halcmd_state_t hc;

void halcmd_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void halcmd_info(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void halcmd_output(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Execute one tokenized command; 0 on success. */
int halcmd_dispatch(int argc, char **argv);
/* Execute one raw line (preprocess + tokenize + dispatch). */
int halcmd_run_line(const char *line);
/* Run the commands of an open file (stdin, -f). */
int halcmd_run_file(const char *path, FILE *f);
/* Open and run a file (-f FILE, source): refuses directories and `source`
 * loops, and nesting deeper than 16 files. */
int halcmd_source(const char *path, int top);

/* show/list/save/status (halcmd_show.c) */
int do_show_cmd(int argc, char **argv);
int do_list_cmd(int argc, char **argv);
int do_save_cmd(int argc, char **argv);
int do_status_cmd(int argc, char **argv);

/* Names for completion (halcmd_main.c). */
extern const char *const halcmd_command_names[];

#endif /* HM_HALCMD_H */
