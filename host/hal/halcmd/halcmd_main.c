/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd - the HAL command interpreter (see docs/halcmd.md).
 *
 *   halcmd [options] [command [args]]
 *   halcmd [options] -f [filename]
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
#include "halcmd_parse.h"
#include "rtapi_proto.h"

static void usage(void)
{
    printf("Usage:   halcmd [options] [cmd [args]]\n"
           "         halcmd [options] -f [filename]\n\n"
           "options:\n"
           "  -e             echo the commands from the file/stdin to stderr\n"
           "  -f [filename]  read commands from 'filename' (stdin if none)\n"
           "  -i filename    INI file for [SECTION]KEY substitution\n"
           "  -k             keep going after a failed command\n"
           "  -q             quiet: print errors only (default)\n"
           "  -Q             very quiet: print nothing\n"
           "  -R             release the HAL mutex (crash recovery only)\n"
           "  -s             script friendly: no headers in show output\n"
           "  -S, --simclock run the session on the simulated clock\n"
           "  -v             verbose: report every successful command\n"
           "  -V             very verbose\n"
           "  -h [command]   help\n\n"
           "Session (HAL_INSTANCE=%s): --session-state, --session-destroy (used by halrun)\n\n"
           "commands: loadrt, loadusr, waitusr, unload, unloadrt, unloadusr, lock, unlock,\n"
           "  net, linkpp, linkps, linksp, unlinkp, alias, unalias, newsig, delsig, setp,\n"
           "  getp, ptype, sets, gets, stype, addf, delf, show, list, save, status, start,\n"
           "  stop, source, echo, unecho, quit, exit, debug, print, simrun, help\n",
           hal_priv_instance());
}

#ifdef HAVE_READLINE
static char **completion_names;
static int completion_count;

static int add_name(const char *name, void *ctx)
{
    (void)ctx;
    char **v = realloc(completion_names, sizeof(char *) * (size_t)(completion_count + 2));
    if (v == NULL)
        return 1;
    completion_names = v;
    completion_names[completion_count++] = strdup(name);
    completion_names[completion_count] = NULL;
    return 0;
}

static char *name_generator(const char *text, int state)
{
    static int idx;
    static size_t len;
    if (!state) {
        idx = 0;
        len = strlen(text);
    }
    while (completion_names && idx < completion_count) {
        const char *n = completion_names[idx++];
        if (strncmp(n, text, len) == 0)
            return strdup(n);
    }
    return NULL;
}

static char *command_generator(const char *text, int state)
{
    static int idx;
    static size_t len;
    if (!state) {
        idx = 0;
        len = strlen(text);
    }
    const char *n;
    while ((n = halcmd_command_names[idx]) != NULL) {
        idx++;
        if (strncmp(n, text, len) == 0)
            return strdup(n);
    }
    return NULL;
}

static char **halcmd_completion(const char *text, int start, int end)
{
    (void)end;
    rl_attempted_completion_over = 1;
    int first = 1;
    for (int i = 0; i < start; i++)
        if (rl_line_buffer[i] != ' ' && rl_line_buffer[i] != '\t')
            first = 0;
    if (first)
        return rl_completion_matches(text, command_generator);
    for (int i = 0; i < completion_count; i++)
        free(completion_names[i]);
    free(completion_names);
    completion_names = NULL;
    completion_count = 0;
    static const char *const kw[] = {"pin", "sig", "param", "funct", "thread", "comp",
                                     "alias", "all", "=>", "<=", "<=>", NULL};
    for (int i = 0; kw[i]; i++)
        add_name(kw[i], NULL);
    hal_q_kind_t kinds[] = {HAL_Q_PIN, HAL_Q_SIG, HAL_Q_PARAM, HAL_Q_FUNCT, HAL_Q_THREAD,
                            HAL_Q_COMP};
    for (size_t k = 0; k < sizeof(kinds) / sizeof(kinds[0]); k++)
        hal_q_foreach(kinds[k], text, add_name, NULL);
    return rl_completion_matches(text, name_generator);
}
#endif

static int interactive(void)
{
    int result = 0;
    hc.filename = "<stdin>";
    hc.linenum = 0;
#ifdef HAVE_READLINE
    rl_readline_name = "halcmd";
    rl_attempted_completion_function = halcmd_completion;
    while (!hc.done) {
        char *line = readline("halcmd: ");
        if (line == NULL)
            break;
        if (*line)
            add_history(line);
        hc.linenum++;
        int rc = halcmd_run_line(line);
        free(line);
        if (rc)
            result = rc;
    }
#else
    char *line = malloc(HALCMD_MAX_LINE);
    if (line == NULL)
        return -ENOMEM;
    while (!hc.done) {
        printf("halcmd: ");
        fflush(stdout);
        char err[128];
        int got = halcmd_read_line(stdin, line, HALCMD_MAX_LINE, &hc.linenum, err, sizeof(err));
        if (got < 0) {
            halcmd_error("%s\n", err);
            result = -EINVAL;
            break;
        }
        if (got == 0)
            break;
        int rc = halcmd_run_line(line);
        if (rc)
            result = rc;
    }
    free(line);
#endif
    printf("\n");
    return result;
}


int main(int argc, char **argv)
{
    int use_file = 0, release = 0, help = 0;
    int i = 1;
    for (; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--simclock") == 0) {
            setenv("HAL_SIMCLOCK", "1", 1);
            continue;
        }
        if (strcmp(a, "--session-state") == 0) {
            static const char *const names[] = {"none", "running", "stale", "idle"};
            int st = hal_priv_session_state();
            printf("%s\n", names[st]);
            return st;
        }
        if (strcmp(a, "--session-rtapi-pid") == 0) {
            printf("%d\n", hal_priv_session_rtapi_pid());
            return 0;
        }
        if (strcmp(a, "--session-rtapi-alive") == 0) {
            int fd = rtapi_client_connect(0);
            if (fd >= 0)
                close(fd);
            return fd >= 0 ? 0 : 1;
        }
        if (strcmp(a, "--session-kill") == 0) {
            /* Ask rtapi_app to unload and leave, then make sure. */
            const char *av[] = {"exit"};
            int st;
            char *msgs = NULL;
            if (rtapi_client_request_timeout(0, 1, av, &st, &msgs, 2000) == 0)
                free(msgs);
            hal_priv_session_kill();
            return 0;
        }
        if (strcmp(a, "--session-end") == 0) {
            /* halrun's epilogue in one process: stop, unload all, wait
             * for rtapi_app to leave, remove the session. */
            if (hal_priv_session_state() == 0)
                return 0;
            int rc = 0;
            if (hal_priv_attach() == 0) {
                snprintf(hc.comp_name, sizeof(hc.comp_name), "halcmd%d", (int)getpid());
                hc.comp_id = hal_init(hc.comp_name);
                char *stop[] = {"stop", NULL};
                char *unload[] = {"unload", "all", NULL};
                if (halcmd_dispatch(1, stop))
                    rc = 1;
                if (halcmd_dispatch(2, unload))
                    rc = 1;
                if (hc.comp_id > 0)
                    hal_exit(hc.comp_id);
            }
            for (int t = 0; t < 5000; t++) {
                int pid = hal_priv_session_rtapi_pid();
                if (pid <= 0 || !hal_priv_pid_alive(pid))
                    break;
                usleep(1000);
            }
            hal_priv_session_destroy();
            return rc;
        }
        if (strcmp(a, "--session-destroy") == 0) {
            hal_priv_session_destroy();
            return 0;
        }
        if (strcmp(a, "--") == 0) {
            i++;
            break;
        }
        if (a[0] != '-' || a[1] == '\0')
            break;
        if (strcmp(a, "-i") == 0) {
            if (i + 1 >= argc) {
                fprintf(stderr, "halcmd: -i needs an INI file name\n");
                return 1;
            }
            hc.ini = argv[++i];
            continue;
        }
        for (const char *o = a + 1; *o; o++) {
            switch (*o) {
            case 'e': hc.echo = 1; break;
            case 'f': use_file = 1; break;
            case 'k': hc.keep_going = 1; break;
            case 'q': hc.quiet = 1; break;
            case 'Q': hc.very_quiet = 1; break;
            case 'R': release = 1; break;
            case 's': hc.script = 1; break;
            case 'S': setenv("HAL_SIMCLOCK", "1", 1); break;
            case 'v': hc.verbose = 1; break;
            case 'V': hc.verbose = hc.very_verbose = 1; break;
            case 'h': help = 1; break;
            case 'i':
                if (o[1] != '\0') {
                    hc.ini = o + 1;
                } else if (i + 1 < argc) {
                    hc.ini = argv[++i];
                } else {
                    fprintf(stderr, "halcmd: -i needs an INI file name\n");
                    return 1;
                }
                goto next_arg;
            default:
                fprintf(stderr, "halcmd: unknown option '-%c'\n", *o);
                usage();
                return 1;
            }
        }
    next_arg:;
    }
    if (help) {
        if (i < argc) {
            char *av[] = {"help", argv[i], NULL};
            return halcmd_dispatch(2, av) ? 1 : 0;
        }
        usage();
        return 0;
    }
    if (hc.ini != NULL) {
        struct stat st;
        if (access(hc.ini, R_OK) != 0 || stat(hc.ini, &st) != 0) {
            fprintf(stderr, "halcmd: cannot read INI file '%s': %s\n", hc.ini, strerror(errno));
            return 1;
        }
        if (!S_ISREG(st.st_mode)) {
            fprintf(stderr, "halcmd: INI file '%s' is not a regular file\n", hc.ini);
            return 1;
        }
    }
    if (hal_priv_attach() != 0)
        return 1;
    if (release)
        hal_priv_force_unlock();
    int dead = 0;
    if (hal_priv_rt_lost(&dead)) {
        fprintf(stderr,
                "halcmd: the realtime host of HAL session '%s' (rtapi_app, pid %d) is gone "
                "(killed or crashed): its realtime components and threads no longer run.\n"
                "Run 'halrun -U' to clean up the session.\n",
                hal_priv_instance(), dead);
        return 1;
    }
    const char *want_sim = getenv("HAL_SIMCLOCK");
    if (want_sim && *want_sim && strcmp(want_sim, "0") != 0 && !hal_q_simclock()) {
        fprintf(stderr, "halcmd: HAL session %s already runs on the wall clock; "
                        "cannot switch it to the simulated clock\n",
                hal_priv_instance());
        return 1;
    }
    signal(SIGPIPE, SIG_IGN);

    snprintf(hc.comp_name, sizeof(hc.comp_name), "halcmd%d", (int)getpid());
    hc.comp_id = hal_init(hc.comp_name);
    if (hc.comp_id < 0) {
        fprintf(stderr, "halcmd: hal_init() failed: %d\n", hc.comp_id);
        return 1;
    }
    hal_ready(hc.comp_id);

    int rc = 0;
    if (use_file) {
        if (i < argc) {
            rc = halcmd_source(argv[i], 1);
        } else if (isatty(0)) {
            rc = interactive();
        } else {
            rc = halcmd_run_file("<stdin>", stdin);
        }
    } else if (i < argc) {
        hc.filename = NULL;
        rc = halcmd_dispatch(argc - i, argv + i);
    } else {
        rc = isatty(0) ? interactive() : halcmd_run_file("<stdin>", stdin);
    }
    fflush(stdout);
    hal_exit(hc.comp_id);
    /* On its own (not under halrun, which ends the session itself), the
     * last halcmd leaving an empty session removes it: `halcmd loadrt
     * and2; halcmd unload all` leaves nothing behind. */
    const char *in_halrun = getenv("HAL_HALRUN");
    if (in_halrun == NULL || in_halrun[0] == '\0')
        hal_priv_session_release();
    return rc ? 1 : 0;
}
