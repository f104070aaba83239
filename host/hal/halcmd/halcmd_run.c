/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_run.c - running halcmd input: the command table and dispatch,
 * help, lines (substitution, tokens, echo), files and `source` (with loop
 * and depth checks), and the output helpers every command uses.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "halcmd.h"
#include "halcmd_parse.h"
#include "rtapi_proto.h"

halcmd_state_t hc;

static void vprefix(FILE *out, const char *fmt, va_list ap)
{
    fflush(stdout);
    if (hc.filename != NULL)
        fprintf(out, "%s:%d: ", hc.filename, hc.linenum);
    else if (out != hc.err)
        fprintf(out, "<commandline>:0: ");
    vfprintf(out, fmt, ap);
    fflush(out);
}

FILE *halcmd_stdout(void) { return hc.out != NULL ? hc.out : stdout; }

void halcmd_error(const char *fmt, ...)
{
    if (hc.very_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    vprefix(hc.err != NULL ? hc.err : stderr, fmt, ap);
    va_end(ap);
}

void halcmd_info(const char *fmt, ...)
{
    if (!hc.verbose || hc.very_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    vprefix(halcmd_stdout(), fmt, ap);
    va_end(ap);
}

void halcmd_output(const char *fmt, ...)
{
    if (hc.very_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    vfprintf(halcmd_stdout(), fmt, ap);
    va_end(ap);
}

/* Messages of realtime modules, as rtapi_app captured them: NUL-separated
 * records tagged 'E' (stderr) or 'O' (stdout). */
void print_rt_messages(const char *msgs)
{
    if (msgs == NULL)
        return;
    for (const char *p = msgs; *p != '\0'; p += strlen(p) + 1) {
        if (hc.very_quiet)
            continue;
        FILE *f = p[0] == 'O' ? stdout : stderr;
        fflush(f == stdout ? stderr : stdout);
        fputs(p + 1, f);
        fflush(f);
    }
}

/* ---- misc ----------------------------------------------------------------------- */

int do_source_cmd(int argc, char **argv)
{
    (void)argc;
    return halcmd_source(argv[1], 0);
}

int do_echo_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    hc.echo = 1;
    return 0;
}

int do_unecho_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    hc.echo = 0;
    halcmd_output("Echo off\n");
    return 0;
}

int do_quit_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    hc.done = 1;
    return 0;
}

int do_debug_cmd(int argc, char **argv)
{
    if (argc == 1) {
        halcmd_output("%d\n", rtapi_get_msg_level());
        return 0;
    }
    char *end;
    long v = strtol(argv[1], &end, 10);
    if (*argv[1] == '\0' || *end != '\0' || v < RTAPI_MSG_NONE || v > RTAPI_MSG_ALL) {
        halcmd_error("debug: level '%s' must be 0..5\n", argv[1]);
        return -EINVAL;
    }
    rtapi_set_msg_level((int)v);
    return 0;
}

int do_print_cmd(int argc, char **argv)
{
    /* LinuxCNC 2.9 prints "(null)" when there is no message. */
    halcmd_error("HALCMD MSG: %s\n", argc > 1 ? argv[1] : "(null)");
    return 0;
}

static int do_help_cmd(int argc, char **argv);

typedef struct {
    const char *name;
    int (*fn)(int, char **);
    int min, max; /* argument counts (not counting the command); max -1 = any */
    const char *usage;
} cmd_t;

static const cmd_t commands[] = {
    {"addf", do_addf_cmd, 2, 3, "addf functname threadname [position]"},
    {"alias", do_alias_cmd, 3, 3, "alias pin|param name alias"},
    {"debug", do_debug_cmd, 1, 1, "debug level (0 none, 1 errors, 2 warnings, 3 info, 4 debug, 5 all)"},
    {"delf", do_delf_cmd, 2, 2, "delf functname threadname"},
    {"delsig", do_delsig_cmd, 1, 1, "delsig signame|all"},
    {"echo", do_echo_cmd, 0, 0, "echo"},
    {"exit", do_quit_cmd, 0, 0, "exit"},
    {"getp", do_getp_cmd, 1, 1, "getp paramname|pinname"},
    {"gets", do_gets_cmd, 1, 1, "gets signame"},
    {"help", do_help_cmd, 0, 1, "help [command]"},
    {"linkpp", do_linkpp_cmd, 2, 2, "linkpp firstpin secondpin (deprecated: use net)"},
    {"linkps", do_linkps_cmd, 2, 2, "linkps pinname signame"},
    {"linksp", do_linksp_cmd, 2, 2, "linksp signame pinname"},
    {"list", do_list_cmd, 1, -1, "list comp|pin|sig|param|funct|thread [-tTYPE] [pattern...]"},
    {"loadrt", do_loadrt_cmd, 1, -1, "loadrt modname [modarg...]"},
    {"loadusr", do_loadusr_cmd, 1, -1, "loadusr [-W|-Wn name|-w|-i|-n name] prog [args...]"},
    {"lock", do_lock_cmd, 0, 1, "lock [all|tune|none]"},
    {"net", do_net_cmd, 1, -1, "net signame [arrow] pinname ..."},
    {"newsig", do_newsig_cmd, 2, 2, "newsig signame bit|float|s32|u32|s64|u64"},
    {"print", do_print_cmd, 0, 1, "print [message]"},
    {"ptype", do_ptype_cmd, 1, 1, "ptype paramname|pinname"},
    {"quit", do_quit_cmd, 0, 0, "quit"},
    {"save", do_save_cmd, 0, 2, "save [type] [filename]"},
    {"setexact_for_test_suite_only", do_setexact_cmd, 0, 0, "setexact_for_test_suite_only"},
    {"setp", do_setp_cmd, 2, 2, "setp paramname|pinname value"},
    {"sets", do_sets_cmd, 2, 2, "sets signame value"},
    {"show", do_show_cmd, 0, -1, "show [comp|pin|sig|param|funct|thread|alias|all] [pattern...]"},
    {"simrun", do_simrun_cmd, 1, 1, "simrun duration (simulated clock only)"},
    {"source", do_source_cmd, 1, 1, "source filename"},
    {"start", do_start_cmd, 0, 0, "start"},
    {"status", do_status_cmd, 0, 1, "status [lock|mem|all]"},
    {"stop", do_stop_cmd, 0, 0, "stop"},
    {"stype", do_stype_cmd, 1, 1, "stype signame"},
    {"unalias", do_unalias_cmd, 2, 2, "unalias pin|param name"},
    {"unecho", do_unecho_cmd, 0, 0, "unecho"},
    {"unlinkp", do_unlinkp_cmd, 1, 1, "unlinkp pinname"},
    {"unload", do_unload_cmd, 1, 1, "unload compname|all"},
    {"unloadrt", do_unloadrt_cmd, 1, 1, "unloadrt modname|all"},
    {"unloadusr", do_unloadusr_cmd, 1, 1, "unloadusr compname|all"},
    {"unlock", do_unlock_cmd, 0, 1, "unlock [all|tune]"},
    {"waitusr", do_waitusr_cmd, 1, 1, "waitusr compname"},
};
#define NCOMMANDS ((int)(sizeof(commands) / sizeof(commands[0])))

const char *const halcmd_command_names[] = {
    "addf", "alias", "debug", "delf", "delsig", "echo", "exit", "getp", "gets", "help",
    "linkpp", "linkps", "linksp", "list", "loadrt", "loadusr", "lock", "net", "newsig",
    "print", "ptype", "quit", "save", "setexact_for_test_suite_only", "setp", "sets", "show",
    "simrun", "source", "start", "status", "stop", "stype", "unalias", "unecho", "unlinkp",
    "unload", "unloadrt", "unloadusr", "unlock", "waitusr", NULL};

static int do_help_cmd(int argc, char **argv)
{
    if (argc == 1) {
        halcmd_output("Use 'help <command>' for more details.\ncommands:\n");
        for (int i = 0; i < NCOMMANDS; i++)
            halcmd_output("  %s\n", commands[i].usage);
        return 0;
    }
    for (int i = 0; i < NCOMMANDS; i++)
        if (strcmp(commands[i].name, argv[1]) == 0) {
            halcmd_output("%s\n", commands[i].usage);
            return 0;
        }
    halcmd_error("No help for unknown command '%s'\n", argv[1]);
    return -EINVAL;
}

int halcmd_dispatch(int argc, char **argv)
{
    if (argc == 0)
        return 0;
    /* "name = value" is setp */
    if (argc == 3 && strcmp(argv[1], "=") == 0) {
        char *av[] = {"setp", argv[0], argv[2], NULL};
        return do_setp_cmd(3, av);
    }
    for (int i = 0; i < NCOMMANDS; i++) {
        const cmd_t *c = &commands[i];
        if (strcmp(c->name, argv[0]) != 0)
            continue;
        int nargs = argc - 1;
        if (c->min == c->max && nargs != c->min) {
            halcmd_error("%s requires %d arguments, %d given\n", c->name, c->min, nargs);
            return -EINVAL;
        }
        if (nargs < c->min) {
            halcmd_error("%s requires at least %d arguments, %d given\n", c->name, c->min,
                         nargs);
            return -EINVAL;
        }
        if (c->max >= 0 && nargs > c->max) {
            halcmd_error("%s requires at most %d arguments, %d given\n", c->name, c->max,
                         nargs);
            return -EINVAL;
        }
        return c->fn(argc, argv);
    }
    halcmd_error("Unknown command '%s'\n", argv[0]);
    return -EINVAL;
}

static char *ini_lookup(const char *section, const char *key, void *ctx)
{
    (void)ctx;
    if (hc.ini == NULL)
        return NULL;
    return halcmd_ini_get(hc.ini, section, key);
}

int halcmd_run_line(const char *line)
{
    char *buf = malloc(HALCMD_MAX_LINE);
    char **tokens = malloc(HALCMD_MAX_TOKENS * sizeof(char *));
    if (buf == NULL || tokens == NULL) {
        free(buf);
        free(tokens);
        return -ENOMEM;
    }
    char err[256];
    int rc = halcmd_preprocess(line, buf, HALCMD_MAX_LINE, ini_lookup, NULL, err, sizeof(err));
    if (rc == 0) {
        int n = halcmd_tokenize(buf, tokens, HALCMD_MAX_TOKENS, err, sizeof(err));
        if (n < 0) {
            halcmd_error("%s\n", err);
            rc = -EINVAL;
        } else {
            if (hc.echo && n > 0) {
                fflush(stdout);
                for (int i = 0; i < n; i++)
                    fprintf(stderr, "%s%s", i ? " " : "", tokens[i]);
                fprintf(stderr, "\n");
            }
            rc = halcmd_dispatch(n, tokens);
        }
    } else {
        halcmd_error("%s\n", err);
        rc = -EINVAL;
    }
    free(buf);
    free(tokens);
    return rc;
}

int halcmd_run_file(const char *path, FILE *f)
{
    hc.filename = path;
    hc.linenum = 0;
    char *logical = malloc(HALCMD_MAX_LINE);
    if (logical == NULL)
        return -ENOMEM;
    int result = 0;
    while (!hc.done) {
        char err[128];
        /* Errors name the last physical line of a continued line, as
         * LinuxCNC does. */
        int got = halcmd_read_line(f, logical, HALCMD_MAX_LINE, &hc.linenum, err, sizeof(err));
        if (got == 0)
            break;
        if (got < 0) {
            /* Not a HAL file (or unreadable): stop even with -k. */
            halcmd_error("%s\n", err);
            result = -EINVAL;
            break;
        }
        int rc = halcmd_run_line(logical);
        if (rc != 0) {
            result = rc;
            if (!hc.keep_going)
                break;
        }
    }
    free(logical);
    return result;
}

/* The files being read, outermost first, to refuse a `source` loop. */
#define SOURCE_MAX_DEPTH 16
static struct {
    const char *name;
    dev_t dev;
    ino_t ino;
} source_stack[SOURCE_MAX_DEPTH];
static int source_depth;

static void source_chain(char *buf, size_t len, const char *last)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; i < source_depth && n < len; i++)
        n += (size_t)snprintf(buf + n, len - n, "%s -> ", source_stack[i].name);
    if (n < len)
        snprintf(buf + n, len - n, "%s", last);
}

/* LinuxCNC 2.9's messages, without a file:line prefix: "Could not open
 * command file 'X'" (-f) and "Could not open hal file 'X': REASON"
 * (source).  A directory is named as such. */
static void open_error(int top, const char *path, int e)
{
    if (hc.very_quiet)
        return;
    fflush(stdout);
    if (top && e == ENOENT)
        fprintf(stderr, "Could not open command file '%s'\n", path);
    else
        fprintf(stderr, "Could not open %s file '%s': %s\n", top ? "command" : "hal", path,
                strerror(e));
}

int halcmd_source(const char *path, int top)
{
    FILE *f = fopen(path, "re"); /* children (loadusr) must not share its offset */
    if (f == NULL) {
        int e = errno;
        open_error(top, path, e);
        return -e;
    }
    struct stat st;
    if (fstat(fileno(f), &st) != 0 || S_ISDIR(st.st_mode)) {
        int e = S_ISDIR(st.st_mode) ? EISDIR : errno;
        fclose(f);
        open_error(top, path, e);
        return -e;
    }
    char chain[1024];
    for (int i = 0; i < source_depth; i++) {
        if (source_stack[i].dev == st.st_dev && source_stack[i].ino == st.st_ino) {
            fclose(f);
            source_chain(chain, sizeof(chain), path);
            halcmd_error("source: '%s' is already being read (a loop): %s\n", path, chain);
            return -ELOOP;
        }
    }
    if (source_depth >= SOURCE_MAX_DEPTH) {
        fclose(f);
        source_chain(chain, sizeof(chain), path);
        halcmd_error("source: files nested more than %d deep: %s\n", SOURCE_MAX_DEPTH, chain);
        return -ELOOP;
    }
    source_stack[source_depth].name = path;
    source_stack[source_depth].dev = st.st_dev;
    source_stack[source_depth].ino = st.st_ino;
    source_depth++;
    const char *saved_name = hc.filename;
    int saved_line = hc.linenum;
    int rc = halcmd_run_file(path, f);
    hc.filename = saved_name;
    hc.linenum = saved_line;
    source_depth--;
    fclose(f);
    return rc;
}

