/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_usr.c - userspace programs and components: loadusr (waiting
 * for ready or exit, and cleaning up after a program that fails or is
 * interrupted), waitusr, unloadusr, unload.
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

/* ---- user components ----------------------------------------------------- */

typedef struct {
    int pids[1024];
    char names[1024][HAL_NAME_LEN + 1];
    int n;
} user_comps_t;

static int collect_user(const char *name, void *ctx)
{
    user_comps_t *u = ctx;
    hal_q_comp_t c;
    if (hal_q_comp(name, &c) == 0 && !c.realtime && c.pid != getpid() && u->n < 1024) {
        u->pids[u->n] = c.pid;
        snprintf(u->names[u->n], HAL_NAME_LEN + 1, "%s", c.name);
        u->n++;
    }
    return 0;
}

static void sleep_ms(int ms)
{
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}


/* A signal (Ctrl-C, SIGTERM, SIGHUP) that ends a wait for a program. */
static volatile sig_atomic_t interrupted;

static void on_interrupt(int sig) { interrupted = sig; }

static void catch_interrupts(int on)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on ? on_interrupt : SIG_DFL;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
}

/* Remove the components a (dead) process left in HAL. */
static void remove_comps_of(int pid)
{
    user_comps_t *u = calloc(1, sizeof(*u));
    if (u == NULL)
        return;
    hal_q_foreach(HAL_Q_COMP, NULL, collect_user, u);
    for (int i = 0; i < u->n; i++) {
        hal_q_comp_t c;
        if (u->pids[i] == pid && hal_q_comp(u->names[i], &c) == 0)
            halpr_comp_delete(c.id);
    }
    free(u);
}

/* Stop a program started by loadusr that we give up on, and everything
 * it put into HAL, so no process and no stale component is left. */
static void stop_child(pid_t pid)
{
    int st;
    if (waitpid(pid, &st, WNOHANG) == 0) {
        kill(pid, SIGTERM);
        for (int t = 0; t < 200 && waitpid(pid, &st, WNOHANG) == 0; t++)
            sleep_ms(10);
        if (waitpid(pid, &st, WNOHANG) == 0) {
            kill(pid, SIGKILL);
            waitpid(pid, &st, 0);
        }
    }
    remove_comps_of(pid);
}

static int interrupted_wait(pid_t pid, const char *prog)
{
    stop_child(pid);
    halcmd_error("loadusr: interrupted (signal %d) while waiting for '%s'; stopped it\n",
                 (int)interrupted, prog);
    hc.done = 1; /* the whole run was interrupted */
    return -EINTR;
}

/* Remove the component of a process that died without hal_exit. */
static void reap_dead_comp(const char *name)
{
    hal_q_comp_t c;
    if (hal_q_comp(name, &c) == 0 && !c.realtime && !hal_priv_pid_alive(c.pid))
        halpr_comp_delete(c.id);
}

static int unloadusr_common(const char *which)
{
    user_comps_t *u = calloc(1, sizeof(*u));
    if (u == NULL)
        return -ENOMEM;
    hal_q_foreach(HAL_Q_COMP, NULL, collect_user, u);
    int found = 0;
    for (int i = 0; i < u->n; i++) {
        if (strcmp(which, "all") != 0 && strcmp(which, u->names[i]) != 0)
            continue;
        found = 1;
        if (hal_priv_pid_alive(u->pids[i]))
            kill(u->pids[i], SIGTERM);
    }
    /* Wait (up to 5 s) for them to leave HAL. */
    for (int t = 0; t < 500; t++) {
        int left = 0;
        for (int i = 0; i < u->n; i++) {
            if (strcmp(which, "all") != 0 && strcmp(which, u->names[i]) != 0)
                continue;
            reap_dead_comp(u->names[i]);
            if (hal_q_component_exists(u->names[i]))
                left = 1;
        }
        if (!left)
            break;
        sleep_ms(10);
    }
    free(u);
    if (!found && strcmp(which, "all") != 0) {
        halcmd_error("component '%s' not found or not a user space component\n", which);
        return -ENOENT;
    }
    return 0;
}

int do_unloadusr_cmd(int argc, char **argv)
{
    (void)argc;
    return unloadusr_common(argv[1]);
}

int do_unload_cmd(int argc, char **argv)
{
    (void)argc;
    if (strcmp(argv[1], "all") == 0) {
        int r1 = unloadusr_common("all");
        int r2 = unloadrt_all();
        return r1 ? r1 : r2;
    }
    hal_q_comp_t c;
    if (hal_q_comp(argv[1], &c) != 0) {
        halcmd_error("component '%s' not found\n", argv[1]);
        return -ENOENT;
    }
    if (!c.realtime)
        return unloadusr_common(argv[1]);
    char *av[] = {"unloadrt", argv[1], NULL};
    return do_unloadrt_cmd(2, av);
}

static char *find_program(const char *prog)
{
    if (strchr(prog, '/') != NULL)
        return strdup(prog);
    /* Our own bin directory first, then PATH. */
    char self[4096];
    ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
    if (n > 0) {
        self[n] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) {
            *slash = '\0';
            char *cand;
            if (asprintf(&cand, "%s/%s", self, prog) > 0) {
                if (access(cand, X_OK) == 0)
                    return cand;
                free(cand);
            }
        }
    }
    const char *path = getenv("PATH");
    if (path == NULL)
        return NULL;
    char *dirs = strdup(path), *save = NULL;
    for (char *d = strtok_r(dirs, ":", &save); d; d = strtok_r(NULL, ":", &save)) {
        char *cand;
        if (asprintf(&cand, "%s/%s", d, prog) < 0)
            continue;
        struct stat st;
        if (access(cand, X_OK) == 0 && stat(cand, &st) == 0 && S_ISREG(st.st_mode)) {
            free(dirs);
            return cand;
        }
        free(cand);
    }
    free(dirs);
    return NULL;
}

static int wait_for_ready(pid_t pid, const char *prog, const char *wait_name);
static int wait_for_exit(pid_t pid, const char *prog, int ignore_rc);

int do_loadusr_cmd(int argc, char **argv)
{
    int wait_ready = 0, wait_exit = 0, ignore_rc = 0;
    const char *wait_name = NULL;
    int i = 1;
    for (; i < argc && argv[i][0] == '-'; i++) {
        const char *o = argv[i] + 1;
        if (strcmp(o, "Wn") == 0 || strcmp(o, "n") == 0) {
            if (i + 1 >= argc) {
                halcmd_error("loadusr: -%s needs a component name\n", o);
                return -EINVAL;
            }
            wait_name = argv[++i];
            if (o[0] == 'W')
                wait_ready = 1;
            continue;
        }
        for (; *o; o++) {
            if (*o == 'W')
                wait_ready = 1;
            else if (*o == 'w')
                wait_exit = 1;
            else if (*o == 'i')
                ignore_rc = 1;
            else {
                halcmd_error("loadusr: unknown option '-%c'\n", *o);
                return -EINVAL;
            }
        }
    }
    if (i >= argc) {
        halcmd_error("loadusr: missing program name\n");
        return -EINVAL;
    }
    if (hal_get_lock() & HAL_LOCK_LOAD) {
        halcmd_error("HAL is locked, loading of programs is not permitted\n");
        return -EPERM;
    }
    const char *prog = argv[i];
    char *path = find_program(prog);
    if (path == NULL) {
        halcmd_error("Can't find program '%s'\n", prog);
        return -ENOENT;
    }
    char cname[HAL_NAME_LEN + 1];
    if (wait_name == NULL) {
        const char *base = strrchr(prog, '/');
        snprintf(cname, sizeof(cname), "%s", base ? base + 1 : prog);
        wait_name = cname;
    }
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) {
        free(path);
        halcmd_error("loadusr: fork failed: %s\n", strerror(errno));
        return -errno;
    }
    if (pid == 0) {
        /* Python components find the hal module of this build. */
        char self[4096];
        ssize_t sn = readlink("/proc/self/exe", self, sizeof(self) - 1);
        if (sn > 0) {
            self[sn] = '\0';
            char *slash = strrchr(self, '/');
            if (slash) {
                *slash = '\0';
                const char *old = getenv("PYTHONPATH");
                char *pp;
                if (asprintf(&pp, "%s/../lib/python%s%s", self, old && *old ? ":" : "",
                             old ? old : "") > 0)
                    setenv("PYTHONPATH", pp, 1);
            }
        }
        char **av = calloc((size_t)(argc - i) + 1, sizeof(char *));
        if (av == NULL)
            _exit(127);
        for (int k = i; k < argc; k++)
            av[k - i] = argv[k];
        execv(path, av);
        fprintf(stderr, "execv(%s): %s\n", path, strerror(errno));
        _exit(127);
    }
    free(path);
    catch_interrupts(1);
    int rc = wait_ready ? wait_for_ready(pid, prog, wait_name) : 0;
    if (rc == 0 && wait_exit)
        rc = wait_for_exit(pid, prog, ignore_rc);
    catch_interrupts(0);
    return rc;
}

static int wait_for_ready(pid_t pid, const char *prog, const char *wait_name)
{
    {
        int ready = 0, hinted = 0;
        for (int t = 0; !ready; t++) {
            if (hal_q_component_ready(wait_name)) {
                ready = 1;
                break;
            }
            if (interrupted)
                return interrupted_wait(pid, prog);
            int st;
            if (waitpid(pid, &st, WNOHANG) == pid) {
                remove_comps_of(pid);
                halcmd_error("%s exited without becoming ready\n", prog);
                return -ECHILD;
            }
            if (t == 100) {
                fflush(stdout);
                fprintf(stderr, "Waiting for component '%s' to become ready.\n", wait_name);
            }
            if (t >= 100 && !hinted) {
                /* The program made a component under another name? */
                user_comps_t *u = calloc(1, sizeof(*u));
                if (u != NULL) {
                    hal_q_foreach(HAL_Q_COMP, NULL, collect_user, u);
                    for (int k = 0; k < u->n && !hinted; k++)
                        if (u->pids[k] == pid && strcmp(u->names[k], wait_name) != 0) {
                            fflush(stdout);
                            fprintf(stderr,
                                    "While waiting for '%s', component '%s' loaded.\n"
                                    "Did you specify the correct name via 'loadusr -Wn'?\n",
                                    wait_name, u->names[k]);
                            hinted = 1;
                        }
                    free(u);
                }
            }
            sleep_ms(10);
        }
        halcmd_info("Component '%s' ready\n", wait_name);
    }
    return 0;
}

static int wait_for_exit(pid_t pid, const char *prog, int ignore_rc)
{
    int st;
    while (waitpid(pid, &st, 0) < 0) {
        if (errno != EINTR)
            return -errno;
        if (interrupted)
            return interrupted_wait(pid, prog);
    }
    remove_comps_of(pid);
    int code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    if (code != 0 && !ignore_rc) {
        halcmd_error("program '%s' failed, returned %d\n", prog, code);
        return -1;
    }
    return 0;
}

int do_waitusr_cmd(int argc, char **argv)
{
    (void)argc;
    hal_q_comp_t c;
    if (hal_q_comp(argv[1], &c) != 0) {
        /* as LinuxCNC 2.9: a component that already left is not an error */
        halcmd_info("component '%s' not found or already exited\n", argv[1]);
        return 0;
    }
    if (c.realtime) {
        halcmd_error("'%s' is not a user space component\n", argv[1]);
        return -EINVAL;
    }
    catch_interrupts(1);
    while (hal_q_component_exists(argv[1])) {
        if (interrupted) {
            catch_interrupts(0);
            halcmd_error("waitusr: interrupted (signal %d) while waiting for '%s'\n",
                         (int)interrupted, argv[1]);
            hc.done = 1;
            return -EINTR;
        }
        reap_dead_comp(argv[1]);
        /* Reap our own children so their pids die. */
        while (waitpid(-1, NULL, WNOHANG) > 0)
            ;
        sleep_ms(10);
    }
    catch_interrupts(0);
    return 0;
}

