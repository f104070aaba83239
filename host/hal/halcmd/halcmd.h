/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd.h - shared state and helpers of halcmd's parts.
 */
#ifndef HM_HALCMD_H
#define HM_HALCMD_H

#include <stdio.h>

#include "hal.h"
#include "hal_query.h"
#include "hal_session.h"

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
    /* Where output and error messages go (NULL: stdout, stderr).  haltcl
     * points them at memory streams to make a command's output its Tcl
     * result and its error message the Tcl error; an error of a command
     * not read from a file then carries no "<commandline>:0: " prefix. */
    FILE *out;
    FILE *err;
} halcmd_state_t;

extern halcmd_state_t hc;

void halcmd_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void halcmd_info(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void halcmd_output(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* The stream command output goes to (hc.out, or stdout). */
FILE *halcmd_stdout(void);

/* Execute one tokenized command; 0 on success. */
int halcmd_dispatch(int argc, char **argv);
/* Execute one raw line (preprocess + tokenize + dispatch). */
int halcmd_run_line(const char *line);
/* Run the commands of an open file (stdin, -f). */
int halcmd_run_file(const char *path, FILE *f);
/* Open and run a file (-f FILE, source): refuses directories and `source`
 * loops, and nesting deeper than 16 files. */
int halcmd_source(const char *path, int top);

/* Messages of realtime modules as rtapi_app captured them (halcmd_run.c). */
void print_rt_messages(const char *msgs);

/* Commands: each gets the tokens of its line (argv[0] = command name) with
 * the argument count already checked against the command table; 0 on
 * success, -errno otherwise, after printing what failed and why. */
/* halcmd_run.c */
int do_source_cmd(int argc, char **argv);
int do_echo_cmd(int argc, char **argv);
int do_unecho_cmd(int argc, char **argv);
int do_quit_cmd(int argc, char **argv);
int do_debug_cmd(int argc, char **argv);
int do_print_cmd(int argc, char **argv);
/* halcmd_rt.c */
int do_loadrt_cmd(int argc, char **argv);
int do_unloadrt_cmd(int argc, char **argv);
int do_simrun_cmd(int argc, char **argv);
int unloadrt_all(void);
/* halcmd_usr.c */
int do_loadusr_cmd(int argc, char **argv);
int do_waitusr_cmd(int argc, char **argv);
int do_unloadusr_cmd(int argc, char **argv);
int do_unload_cmd(int argc, char **argv);
/* halcmd_net.c */
int do_net_cmd(int argc, char **argv);
int do_newsig_cmd(int argc, char **argv);
int do_delsig_cmd(int argc, char **argv);
int do_linkps_cmd(int argc, char **argv);
int do_linksp_cmd(int argc, char **argv);
int do_linkpp_cmd(int argc, char **argv);
int do_unlinkp_cmd(int argc, char **argv);
int do_alias_cmd(int argc, char **argv);
int do_unalias_cmd(int argc, char **argv);
/* halcmd_cmds.c */
int do_setp_cmd(int argc, char **argv);
int do_getp_cmd(int argc, char **argv);
int do_ptype_cmd(int argc, char **argv);
int do_sets_cmd(int argc, char **argv);
int do_gets_cmd(int argc, char **argv);
int do_stype_cmd(int argc, char **argv);
int do_addf_cmd(int argc, char **argv);
int do_delf_cmd(int argc, char **argv);
int do_start_cmd(int argc, char **argv);
int do_stop_cmd(int argc, char **argv);
int do_lock_cmd(int argc, char **argv);
int do_unlock_cmd(int argc, char **argv);
int do_setexact_cmd(int argc, char **argv);
/* halcmd_show.c: show, list; halcmd_save.c: save, status */
int do_show_cmd(int argc, char **argv);
int do_list_cmd(int argc, char **argv);
int do_save_cmd(int argc, char **argv);
int do_status_cmd(int argc, char **argv);

/* Names for completion (halcmd_main.c). */
extern const char *const halcmd_command_names[];

#endif /* HM_HALCMD_H */
