/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * haltcl - HAL files written in Tcl (see docs/haltcl.md).
 *
 *   haltcl [-i INI] [FILE [ARGS...]]
 *
 * Runs FILE in a Tcl interpreter that has every halcmd command (the
 * `hal` command and one Tcl command per halcmd command) and the INI
 * file's values as global arrays; without FILE, an interactive Tcl shell.
 * A failing script reports "FILE:LINE: message" and exits 1.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef HAVE_READLINE
#include <readline/history.h>
#include <readline/readline.h>
#endif

#include "halcmd.h"
#include "haltcl.h"

static void usage(FILE *f)
{
    fprintf(f, "Usage: haltcl [-i INI] [FILE [ARGS...]]\n"
               "  -i INI   make the INI file's values Tcl arrays: $::SECTION(KEY)\n"
               "  FILE     run the Tcl HAL file (ARGS become $::argv); without it, an\n"
               "           interactive Tcl shell\n"
               "Every halcmd command is a Tcl command; 'hal CMD ...' reaches any of them\n"
               "(hal list, hal gets, hal source: Tcl has its own list, gets, source).\n");
}

/* ---- the HAL session ---------------------------------------------------------- */

static int session_begin(void)
{
    if (hal_priv_attach() != 0)
        return -1;
    int dead = 0;
    if (hal_priv_rt_lost(&dead)) {
        fprintf(stderr,
                "haltcl: the realtime host of HAL session '%s' (rtapi_app, pid %d) is gone "
                "(killed or crashed): its realtime components and threads no longer run.\n"
                "Run 'halrun -U' to clean up the session.\n",
                hal_priv_instance(), dead);
        return -1;
    }
    const char *want_sim = getenv("HAL_SIMCLOCK");
    if (want_sim && *want_sim && strcmp(want_sim, "0") != 0 && !hal_q_simclock()) {
        fprintf(stderr,
                "haltcl: HAL session %s already runs on the wall clock; cannot switch it to "
                "the simulated clock\n",
                hal_priv_instance());
        return -1;
    }
    signal(SIGPIPE, SIG_IGN);
    /* The same component name as halcmd's: `show comp` lists it alike. */
    snprintf(hc.comp_name, sizeof(hc.comp_name), "halcmd%d", (int)getpid());
    hc.comp_id = hal_init(hc.comp_name);
    if (hc.comp_id < 0) {
        fprintf(stderr, "haltcl: hal_init() failed: %d\n", hc.comp_id);
        return -1;
    }
    hal_ready(hc.comp_id);
    return 0;
}

/* Run by Tcl_Exit: the end of the script, `exit N`, or the interactive
 * shell's end. */
static void session_end(ClientData cd)
{
    (void)cd;
    fflush(stdout);
    if (hc.comp_id > 0)
        hal_exit(hc.comp_id);
    hc.comp_id = 0;
    /* Outside halrun the last client of an empty session removes it. */
    const char *in_halrun = getenv("HAL_HALRUN");
    if (in_halrun == NULL || in_halrun[0] == '\0')
        hal_priv_session_release();
}

/* ---- errors ------------------------------------------------------------------- */

static Tcl_Obj *dict_get(Tcl_Obj *dict, const char *key)
{
    Tcl_Obj *k = Tcl_NewStringObj(key, -1), *v = NULL;
    Tcl_IncrRefCount(k);
    Tcl_DictObjGet(NULL, dict, k, &v);
    Tcl_DecrRefCount(k);
    return v;
}

/* The innermost `(file "NAME" line N)` of a Tcl error trace. */
static int trace_location(const char *info, char *name, size_t len, int *line)
{
    const char *p = strstr(info, "(file \"");
    if (p == NULL)
        return 0;
    p += 7;
    const char *q = strstr(p, "\" line ");
    if (q == NULL)
        return 0;
    snprintf(name, len, "%.*s", (int)(q - p), p);
    *line = atoi(q + 7);
    return 1;
}

static void report_hal_error(Tcl_Obj *locs, const char *msg)
{
    int n = 0;
    Tcl_ListObjLength(NULL, locs, &n);
    for (int i = 0; i < n; i++) {
        Tcl_Obj *pair, *f, *l;
        Tcl_ListObjIndex(NULL, locs, i, &pair);
        Tcl_ListObjIndex(NULL, pair, 0, &f);
        Tcl_ListObjIndex(NULL, pair, 1, &l);
        if (i == 0)
            fprintf(stderr, "%s:%s: %s\n", Tcl_GetString(f), Tcl_GetString(l), msg);
        else
            fprintf(stderr, "    called from %s:%s\n", Tcl_GetString(f), Tcl_GetString(l));
    }
}

/* "FILE:LINE: message" for a failed script: the location of the failing
 * HAL command (and where it was called from), or for a Tcl error the
 * innermost file line of its trace, followed by the trace. */
static void report_error(Tcl_Interp *interp, int code, const char *script)
{
    Tcl_Obj *opts = Tcl_GetReturnOptions(interp, code);
    Tcl_IncrRefCount(opts);
    const char *msg = Tcl_GetStringResult(interp);
    if (*msg == '\0')
        msg = "error (no message)";
    Tcl_Obj *ecode = dict_get(opts, "-errorcode");
    Tcl_Obj *einfo = dict_get(opts, "-errorinfo");
    Tcl_Obj *kind = NULL, *locs = NULL;
    int n = 0, nlocs = 0;
    if (ecode != NULL && Tcl_ListObjLength(NULL, ecode, &n) == TCL_OK && n == 2) {
        Tcl_ListObjIndex(NULL, ecode, 0, &kind);
        Tcl_ListObjIndex(NULL, ecode, 1, &locs);
        if (strcmp(Tcl_GetString(kind), "HAL") != 0 ||
            Tcl_ListObjLength(NULL, locs, &nlocs) != TCL_OK)
            nlocs = 0;
    }
    fflush(stdout);
    if (nlocs > 0) {
        report_hal_error(locs, msg);
    } else {
        const char *info = einfo != NULL ? Tcl_GetString(einfo) : "";
        char name[4096], cwd[4096];
        int line = 0;
        if (getcwd(cwd, sizeof(cwd)) == NULL)
            cwd[0] = '\0';
        if (trace_location(info, name, sizeof(name), &line))
            fprintf(stderr, "%s:%d: %s\n", haltcl_relative(name, cwd), line, msg);
        else
            fprintf(stderr, "%s: %s\n", script, msg);
        const char *trace = strstr(info, "\n    while executing");
        if (trace == NULL)
            trace = strstr(info, "\n    invoked from within");
        if (trace != NULL)
            fprintf(stderr, "%s\n", trace + 1);
    }
    fflush(stderr);
    Tcl_DecrRefCount(opts);
}

/* ---- interactive -------------------------------------------------------------- */

static char *read_line(const char *prompt)
{
#ifdef HAVE_READLINE
    if (isatty(0)) {
        char *l = readline(prompt);
        if (l != NULL && *l)
            add_history(l);
        return l;
    }
#endif
    (void)prompt;
    char *l = NULL;
    size_t cap = 0;
    ssize_t n = getline(&l, &cap, stdin);
    if (n < 0) {
        free(l);
        return NULL;
    }
    if (n > 0 && l[n - 1] == '\n')
        l[n - 1] = '\0';
    return l;
}

/* Commands read line by line (a command continues until it is complete);
 * results are printed, errors too.  Returns 0. */
static int interactive(Tcl_Interp *interp)
{
    Tcl_Obj *cmd = Tcl_NewObj();
    Tcl_IncrRefCount(cmd);
    for (;;) {
        int partial = Tcl_GetCharLength(cmd) > 0;
        char *line = read_line(partial ? "> " : "haltcl: ");
        if (line == NULL)
            break;
        Tcl_AppendToObj(cmd, line, -1);
        Tcl_AppendToObj(cmd, "\n", 1);
        free(line);
        if (!Tcl_CommandComplete(Tcl_GetString(cmd)))
            continue;
        int code = Tcl_EvalObjEx(interp, cmd, TCL_EVAL_GLOBAL);
        const char *res = Tcl_GetStringResult(interp);
        fflush(stdout);
        if (code == TCL_ERROR)
            fprintf(stderr, "%s\n", res);
        else if (*res)
            printf("%s\n", res);
        fflush(stdout);
        Tcl_DecrRefCount(cmd);
        cmd = Tcl_NewObj();
        Tcl_IncrRefCount(cmd);
    }
    Tcl_DecrRefCount(cmd);
    if (isatty(0))
        printf("\n");
    return 0;
}

/* ---- main --------------------------------------------------------------------- */

static int check_ini(const char *ini)
{
    struct stat st;
    if (access(ini, R_OK) != 0 || stat(ini, &st) != 0) {
        fprintf(stderr, "haltcl: cannot read INI file '%s': %s\n", ini, strerror(errno));
        return -1;
    }
    if (!S_ISREG(st.st_mode)) {
        fprintf(stderr, "haltcl: INI file '%s' is not a regular file\n", ini);
        return -1;
    }
    return 0;
}

static void set_args(Tcl_Interp *interp, const char *argv0, int argc, char **argv)
{
    Tcl_Obj *args = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < argc; i++)
        Tcl_ListObjAppendElement(NULL, args, Tcl_NewStringObj(argv[i], -1));
    Tcl_SetVar2Ex(interp, "argv", NULL, args, TCL_GLOBAL_ONLY);
    Tcl_SetVar2Ex(interp, "argc", NULL, Tcl_NewIntObj(argc), TCL_GLOBAL_ONLY);
    Tcl_SetVar2Ex(interp, "argv0", NULL, Tcl_NewStringObj(argv0, -1), TCL_GLOBAL_ONLY);
}

int main(int argc, char **argv)
{
    const char *ini = NULL;
    int i = 1;
    for (; i < argc && argv[i][0] == '-'; i++) {
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            usage(stdout);
            return 0;
        }
        if ((strcmp(argv[i], "-i") == 0 || strcmp(argv[i], "-ini") == 0) && i + 1 < argc) {
            ini = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--") == 0) {
            i++;
            break;
        }
        fprintf(stderr, "haltcl: unknown option '%s'\n", argv[i]);
        usage(stderr);
        return 1;
    }
    const char *file = i < argc ? argv[i++] : NULL;
    if (ini != NULL && check_ini(ini) != 0)
        return 1;
    if (file != NULL && access(file, R_OK) != 0) {
        fprintf(stderr, "haltcl: cannot read '%s': %s\n", file, strerror(errno));
        return 1;
    }

    Tcl_FindExecutable(argv[0]);
    Tcl_Interp *interp = Tcl_CreateInterp();
    if (Tcl_Init(interp) != TCL_OK) {
        fprintf(stderr, "haltcl: Tcl's library is missing: %s\n", Tcl_GetStringResult(interp));
        return 1;
    }
    if (haltcl_hal_init(interp) != TCL_OK ||
        (ini != NULL && haltcl_ini_arrays(interp, ini) != TCL_OK)) {
        fprintf(stderr, "haltcl: %s\n", Tcl_GetStringResult(interp));
        return 1;
    }
    set_args(interp, file != NULL ? file : argv[0], argc - i, argv + i);
    Tcl_SetVar2Ex(interp, "tcl_interactive", NULL, Tcl_NewIntObj(file == NULL && isatty(0)),
                  TCL_GLOBAL_ONLY);
    if (session_begin() != 0)
        return 1;
    Tcl_CreateExitHandler(session_end, NULL);

    int rc = 0;
    if (file != NULL) {
        int code = Tcl_EvalFile(interp, file);
        if (code == TCL_ERROR) {
            report_error(interp, code, file);
            rc = 1;
        }
    } else {
        rc = interactive(interp);
    }
    Tcl_Exit(rc);
}
