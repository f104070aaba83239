/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_cmds.c - halcmd's commands (except show/list/save/status).
 *
 * Everything except loading/unloading realtime modules and simrun runs in
 * this process directly against the shared segment.  Every command checks
 * all its arguments before changing anything, so a failed command leaves
 * HAL as it was; error texts follow LinuxCNC 2.9's halcmd.
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
    else
        fprintf(out, "<commandline>:0: ");
    vfprintf(out, fmt, ap);
    fflush(out);
}

void halcmd_error(const char *fmt, ...)
{
    if (hc.very_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    vprefix(stderr, fmt, ap);
    va_end(ap);
}

void halcmd_info(const char *fmt, ...)
{
    if (!hc.verbose || hc.very_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    vprefix(stdout, fmt, ap);
    va_end(ap);
}

void halcmd_output(const char *fmt, ...)
{
    if (hc.very_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stdout, fmt, ap);
    va_end(ap);
}

static int is_arrow(const char *s)
{
    return strcmp(s, "=>") == 0 || strcmp(s, "<=") == 0 || strcmp(s, "<=>") == 0 ||
           strcmp(s, "==>") == 0 || strcmp(s, "<==") == 0;
}

/* Messages of realtime modules, as rtapi_app captured them: NUL-separated
 * records tagged 'E' (stderr) or 'O' (stdout). */
static void print_rt_messages(const char *msgs)
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

/* ---- loadrt / unloadrt ----------------------------------------------------- */

/* Component ids are printed by `show`, so they follow LinuxCNC 2.9's
 * sequence: its halcmd runs loadrt through a helper process that takes one
 * id, and re-registers its own component (new id) on every successful
 * loadrt after the first.  A failed loadrt that created nothing takes no
 * id.  ids_before() reserves, ids_after() settles. */
static int ids_before(void)
{
    hal_priv_lock();
    int a = hal_hdr->next_id;
    hal_hdr->next_id += hc.loadrt_done > 0 ? 2 : 1;
    hal_priv_unlock();
    return a;
}

static void ids_after(int a, int ok)
{
    hal_priv_lock();
    if (!ok) {
        if (hal_hdr->next_id == a + (hc.loadrt_done > 0 ? 2 : 1))
            hal_hdr->next_id = a;
        hal_priv_unlock();
        return;
    }
    if (hc.loadrt_done > 0) {
        hal_comp_t *c = halpr_find_comp_by_id(hc.comp_id);
        if (c != NULL) {
            hal_off_t off = SHMOFF(c);
            hal_off_t *pp = &hal_hdr->comp_list;
            while (*pp != off)
                pp = &((hal_comp_t *)SHMPTR(*pp))->next;
            *pp = c->next;
            c->id = a + 1;
            /* the list is newest (highest id) first */
            pp = &hal_hdr->comp_list;
            while (*pp != 0 && ((hal_comp_t *)SHMPTR(*pp))->id > c->id)
                pp = &((hal_comp_t *)SHMPTR(*pp))->next;
            c->next = *pp;
            *pp = off;
            hc.comp_id = c->id;
        }
    }
    hal_priv_unlock();
    hc.loadrt_done++;
}

static int do_loadrt_cmd(int argc, char **argv)
{
    const char *mod = argv[1];
    if (hal_get_lock() & HAL_LOCK_LOAD) {
        halcmd_error("HAL is locked, loading of programs is not permitted\n");
        halcmd_error("insmod for %s failed, returned -1\n", mod);
        return -EPERM;
    }
    int id0 = ids_before();
    const char **av = calloc((size_t)argc + 1, sizeof(char *));
    if (av == NULL)
        return -ENOMEM;
    av[0] = "load";
    for (int i = 1; i < argc; i++)
        av[i] = argv[i];
    int status = 0;
    char *msgs = NULL;
    int rc = rtapi_client_request(1, argc, av, &status, &msgs);
    free(av);
    print_rt_messages(msgs);
    free(msgs);
    ids_after(id0, rc == 0 && status == 0);
    if (rc != 0) {
        halcmd_error("cannot talk to rtapi_app: %s\n", strerror(-rc));
        return rc;
    }
    if (status != 0) {
        halcmd_error("insmod for %s failed, returned -1\n", mod);
        return status;
    }
    /* -v lines as LinuxCNC's halcmd prints them (its loadrt runs
     * rtapi_app as a helper program and waits for the component). */
    if (hc.verbose) {
        if (hal_q_component_exists(mod))
            halcmd_info("Component '%s' ready\n", mod);
        char self[4096];
        ssize_t sn = readlink("/proc/self/exe", self, sizeof(self) - 1);
        if (sn > 0) {
            self[sn] = '\0';
            char *slash = strrchr(self, '/');
            if (slash != NULL)
                strcpy(slash + 1, "rtapi_app");
            halcmd_info("Program '%s' started\n", self);
        }
    }
    halcmd_info("Realtime module '%s' loaded\n", mod);
    return 0;
}

static int rt_module_list(char ***names)
{
    *names = NULL;
    const char *av[] = {"list"};
    int status = 0;
    char *msgs = NULL;
    /* Do not start rtapi_app just to learn that nothing is loaded. */
    int rc = rtapi_client_request(0, 1, av, &status, &msgs);
    if (rc != 0)
        return 0;
    int n = 0;
    for (char *p = msgs; p && *p; p++)
        if (*p == '\n')
            n++;
    char **v = calloc((size_t)n + 1, sizeof(char *));
    int i = 0;
    char *save = NULL;
    for (char *t = msgs ? strtok_r(msgs, "\n", &save) : NULL; t && v && i < n;
         t = strtok_r(NULL, "\n", &save))
        v[i++] = strdup(t);
    free(msgs);
    *names = v;
    return i;
}

static int unloadrt_one(const char *mod)
{
    const char *av[] = {"unload", mod};
    int status = 0;
    char *msgs = NULL;
    int rc = rtapi_client_request(0, 2, av, &status, &msgs);
    print_rt_messages(msgs);
    free(msgs);
    if (rc != 0 || status != 0) {
        halcmd_error("rmmod failed, returned %d\n", rc != 0 ? rc : status);
        return rc != 0 ? rc : status;
    }
    halcmd_info("Realtime module '%s' unloaded\n", mod);
    return 0;
}

static int unloadrt_one_counted(const char *mod)
{
    int id0 = ids_before();
    int rc = unloadrt_one(mod);
    ids_after(id0, rc == 0);
    return rc;
}

static int unloadrt_all(void)
{
    char **names;
    int n = rt_module_list(&names);
    int result = 0;
    /* The list is newest first: unload in reverse load order. */
    for (int i = 0; i < n; i++) {
        int rc = unloadrt_one_counted(names[i]);
        if (rc)
            result = rc;
        free(names[i]);
    }
    free(names);
    return result;
}

static int do_unloadrt_cmd(int argc, char **argv)
{
    (void)argc;
    /* Unloading is allowed while locked (halrun must be able to end). */
    if (strcmp(argv[1], "all") == 0)
        return unloadrt_all();
    char **names;
    int n = rt_module_list(&names);
    int found = 0;
    for (int i = 0; i < n; i++) {
        if (strcmp(names[i], argv[1]) == 0)
            found = 1;
        free(names[i]);
    }
    free(names);
    if (!found) {
        halcmd_error("component '%s' is not loaded\n", argv[1]);
        return -ENOENT;
    }
    return unloadrt_one_counted(argv[1]);
}

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

static int do_unloadusr_cmd(int argc, char **argv)
{
    (void)argc;
    return unloadusr_common(argv[1]);
}

static int do_unload_cmd(int argc, char **argv)
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

static int do_loadusr_cmd(int argc, char **argv)
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

static int do_waitusr_cmd(int argc, char **argv)
{
    (void)argc;
    hal_q_comp_t c;
    if (hal_q_comp(argv[1], &c) != 0) {
        halcmd_error("component '%s' not found\n", argv[1]);
        return -ENOENT;
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

/* ---- net and links ----------------------------------------------------------- */

static int do_newsig_cmd(int argc, char **argv)
{
    (void)argc;
    hal_type_t t = hal_q_type_from_name(argv[2]);
    if (t == HAL_TYPE_UNSPECIFIED) {
        halcmd_error("Unknown signal type '%s'\n", argv[2]);
        halcmd_error("newsig failed\n");
        return -EINVAL;
    }
    if (hal_q_pin(argv[1], NULL) == 0) {
        halcmd_error("Signal name '%s' must not be the same as a pin.\n", argv[1]);
        return -EINVAL;
    }
    int rc = hal_signal_new(argv[1], t);
    if (rc)
        halcmd_error("newsig failed\n");
    return rc;
}

static int do_delsig_cmd(int argc, char **argv)
{
    (void)argc;
    if (strcmp(argv[1], "all") == 0) {
        /* delete every signal */
        for (;;) {
            hal_q_sig_t s;
            char name[HAL_NAME_LEN + 1] = "";
            hal_priv_lock();
            if (hal_hdr->sig_list)
                snprintf(name, sizeof(name), "%s",
                         ((hal_sig_t *)SHMPTR(hal_hdr->sig_list))->name);
            hal_priv_unlock();
            if (name[0] == '\0' || hal_q_sig(name, &s) != 0)
                break;
            int rc = hal_signal_delete(name);
            if (rc)
                return rc;
        }
        return 0;
    }
    return hal_signal_delete(argv[1]);
}

static const char *dir_word(int dir)
{
    return dir == HAL_OUT ? "OUT" : dir == HAL_IO ? "I/O" : "IN";
}

static int do_net_cmd(int argc, char **argv)
{
    const char *sig = argv[1];
    const char *pins[HALCMD_MAX_TOKENS];
    int npins = 0;
    for (int i = 2; i < argc; i++)
        if (!is_arrow(argv[i]))
            pins[npins++] = argv[i];
    if (hal_q_pin(sig, NULL) == 0) {
        halcmd_error("Signal name '%s' must not be the same as a pin.  "
                     "Did you omit the signal name?\n",
                     sig);
        return -EINVAL;
    }
    /* Dry run of the whole command under the lock, then apply.  Messages
     * are LinuxCNC's, also where LinuxCNC would have made half a net. */
    hal_priv_lock();
    hal_sig_t *s = halpr_find_sig_by_name(sig);
    int exists = s != NULL;
    int type = exists ? s->type : HAL_TYPE_UNSPECIFIED;
    int writers = exists ? s->writers : 0, bidirs = exists ? s->bidirs : 0;
    char writer_name[HAL_NAME_LEN + 1] = "", bidir_name[HAL_NAME_LEN + 1] = "";
    if (exists) {
        for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
            hal_pin_t *p = SHMPTR(off);
            if (p->signal == SHMOFF(s) && p->dir == HAL_OUT)
                snprintf(writer_name, sizeof(writer_name), "%s", p->name);
            if (p->signal == SHMOFF(s) && p->dir == HAL_IO && bidir_name[0] == '\0')
                snprintf(bidir_name, sizeof(bidir_name), "%s", p->name);
        }
    }
    if (hal_hdr->lock & HAL_LOCK_CONFIG) {
        hal_priv_unlock();
        if (!exists) {
            rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: signal_new called while HAL is locked\n");
        } else {
            rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: link called while HAL locked\n");
            halcmd_error("link failed\n");
        }
        return -EPERM;
    }
    int rc = 0;
    for (int i = 0; i < npins && rc == 0; i++) {
        hal_pin_t *p = halpr_find_pin_by_name(pins[i]);
        if (p == NULL) {
            hal_priv_unlock();
            halcmd_error("Pin '%s' does not exist\n", pins[i]);
            return -ENOENT;
        }
        if (p->signal != 0 && (!exists || p->signal != SHMOFF(s))) {
            const char *other = ((hal_sig_t *)SHMPTR(p->signal))->name;
            hal_priv_unlock();
            halcmd_error("Pin '%s' was already linked to signal '%s'\n", pins[i], other);
            return -EINVAL;
        }
        if (exists && p->signal == SHMOFF(s))
            continue;
        if (type == HAL_TYPE_UNSPECIFIED)
            type = p->type;
        if (p->type != type) {
            hal_priv_unlock();
            if (exists)
                halcmd_error("Signal '%s' of type '%s' cannot add pin '%s' of type '%s'\n", sig,
                             hal_type_name(type), pins[i], hal_type_name(p->type));
            else {
                rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: type mismatch '%s' <- '%s'\n",
                                pins[i], sig);
                halcmd_error("link failed\n");
            }
            return -EINVAL;
        }
        if (p->dir == HAL_OUT && (writers > 0 || bidirs > 0)) {
            hal_priv_unlock();
            if (exists && writers > 0)
                halcmd_error("Signal '%s' can not add OUT pin '%s', it already has OUT pin '%s'\n",
                             sig, pins[i], writer_name);
            else if (exists)
                halcmd_error("Signal '%s' can not add OUT pin '%s', it already has I/O pin '%s'\n",
                             sig, pins[i], bidir_name);
            else {
                rtapi_print_msg(RTAPI_MSG_ERR,
                                "HAL: ERROR: signal '%s' already has output or I/O pin(s)\n", sig);
                halcmd_error("link failed\n");
            }
            return -EINVAL;
        }
        if (p->dir == HAL_IO && writers > 0) {
            hal_priv_unlock();
            if (exists)
                halcmd_error("Signal '%s' can not add I/O pin '%s', it already has OUT pin '%s'\n",
                             sig, pins[i], writer_name);
            else {
                rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: signal '%s' already has output pin\n",
                                sig);
                halcmd_error("link failed\n");
            }
            return -EINVAL;
        }
        /* The same pin twice in one net is linked once. */
        int dup = 0;
        for (int j = 0; j < i; j++)
            if (halpr_find_pin_by_name(pins[j]) == p)
                dup = 1;
        if (dup)
            continue;
        if (p->dir == HAL_OUT) {
            writers++;
            snprintf(writer_name, sizeof(writer_name), "%s", p->name);
        } else if (p->dir == HAL_IO) {
            bidirs++;
            if (bidir_name[0] == '\0')
                snprintf(bidir_name, sizeof(bidir_name), "%s", p->name);
        }
    }
    hal_priv_unlock();
    if (!exists) {
        if (npins == 0) {
            halcmd_error("net requires at least one pin to create signal '%s'\n", sig);
            return -EINVAL;
        }
        rc = hal_signal_new(sig, (hal_type_t)type);
        if (rc)
            return rc;
    }
    for (int i = 0; i < npins; i++) {
        rc = hal_link(pins[i], sig);
        if (rc == 0)
            halcmd_info("Pin '%s' linked to signal '%s'\n", pins[i], sig);
        if (rc) {
            /* Only a concurrent change can get here; undo what we did. */
            for (int j = 0; j < i; j++)
                hal_unlink(pins[j]);
            if (!exists)
                hal_signal_delete(sig);
            halcmd_error("link failed\n");
            return rc;
        }
    }
    (void)dir_word;
    return 0;
}

static int link_ps(const char *pin, const char *sig)
{
    int rc = hal_link(pin, sig);
    if (rc)
        halcmd_error("link failed\n");
    return rc;
}

/* LinuxCNC 2.9 takes exactly two words (no arrow) for linkps/linksp. */
static int do_linkps_cmd(int argc, char **argv)
{
    (void)argc;
    return link_ps(argv[1], argv[2]);
}

static int do_linksp_cmd(int argc, char **argv)
{
    (void)argc;
    return link_ps(argv[2], argv[1]);
}

/* linkpp P1 P2: a signal named like P1 linking both pins (deprecated in
 * LinuxCNC 2.9, which warns).  All checks first; nothing is made on error. */
static int do_linkpp_cmd(int argc, char **argv)
{
    (void)argc;
    const char *p1 = argv[1], *p2 = argv[2];
    halcmd_error("Warning: linkpp command is deprecated, use 'net'\n");
    hal_q_pin_t a, b;
    if (hal_q_pin(p1, &a) != 0 || hal_q_pin(p2, &b) != 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: pin '%s' not found\n",
                        hal_q_pin(p1, NULL) != 0 ? p1 : p2);
        halcmd_error("link failed\n");
        return -ENOENT;
    }
    if (a.type != b.type) {
        rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: type mismatch '%s' <- '%s'\n", p2, p1);
        halcmd_error("link failed\n");
        return -EINVAL;
    }
    if (a.signal[0] || b.signal[0]) {
        const hal_q_pin_t *l = a.signal[0] ? &a : &b;
        rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: pin '%s' is linked to '%s', cannot link to '%s'\n",
                        l->name, l->signal, p1);
        halcmd_error("link failed\n");
        return -EINVAL;
    }
    int w1 = a.dir == HAL_OUT, w2 = b.dir == HAL_OUT;
    if ((w1 && (w2 || b.dir == HAL_IO)) || (w2 && a.dir == HAL_IO)) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "HAL: ERROR: signal '%s' already has output or I/O pin(s)\n", p1);
        halcmd_error("link failed\n");
        return -EINVAL;
    }
    int rc = hal_signal_new(p1, a.type);
    if (rc == 0 && (rc = hal_link(p1, p1)) == 0 && (rc = hal_link(p2, p1)) != 0) {
        hal_unlink(p1);
    }
    if (rc != 0) {
        if (hal_q_sig(p1, NULL) == 0 && hal_q_sig_pins(p1, NULL, 0) == 0)
            hal_signal_delete(p1);
        halcmd_error("link failed\n");
    }
    return rc;
}

static int do_unlinkp_cmd(int argc, char **argv)
{
    (void)argc;
    int rc = hal_unlink(argv[1]);
    if (rc)
        halcmd_error("unlink failed\n");
    return rc;
}

/* ---- values ------------------------------------------------------------------- */

static int do_setp_cmd(int argc, char **argv)
{
    (void)argc;
    char err[256];
    int rc = hal_q_setp(argv[1], argv[2], err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        if (rc == -EINVAL || rc == -ERANGE)
            halcmd_error("setp failed\n");
    } else {
        halcmd_info("Parameter '%s' set to %s\n", argv[1], argv[2]);
    }
    return rc;
}

static int do_sets_cmd(int argc, char **argv)
{
    (void)argc;
    char err[256];
    int rc = hal_q_sets(argv[1], argv[2], err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        if (rc == -EINVAL || rc == -ERANGE)
            halcmd_error("sets failed\n");
    } else {
        halcmd_info("Signal '%s' set to %s\n", argv[1], argv[2]);
    }
    return rc;
}

static int do_getp_cmd(int argc, char **argv)
{
    (void)argc;
    char buf[64], err[256];
    int rc = hal_q_getp(argv[1], buf, sizeof(buf), NULL, err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        return rc;
    }
    halcmd_output("%s\n", buf);
    return 0;
}

static int do_gets_cmd(int argc, char **argv)
{
    (void)argc;
    char buf[64], err[256];
    int rc = hal_q_gets(argv[1], buf, sizeof(buf), NULL, err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        return rc;
    }
    halcmd_output("%s\n", buf);
    return 0;
}

static int do_ptype_cmd(int argc, char **argv)
{
    (void)argc;
    hal_type_t t;
    char err[256];
    int rc = hal_q_getp(argv[1], NULL, 0, &t, err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        return rc;
    }
    halcmd_output("%s\n", hal_type_name(t));
    return 0;
}

static int do_stype_cmd(int argc, char **argv)
{
    (void)argc;
    hal_type_t t;
    char err[256];
    int rc = hal_q_gets(argv[1], NULL, 0, &t, err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        return rc;
    }
    halcmd_output("%s\n", hal_type_name(t));
    return 0;
}

/* ---- aliases -------------------------------------------------------------------- */

static int do_alias_cmd(int argc, char **argv)
{
    (void)argc;
    int rc;
    if (strcmp(argv[1], "pin") == 0)
        rc = hal_pin_alias(argv[2], argv[3]);
    else if (strcmp(argv[1], "param") == 0)
        rc = hal_param_alias(argv[2], argv[3]);
    else {
        halcmd_error("Unknown alias type '%s'\n", argv[1]);
        return -EINVAL;
    }
    if (rc)
        halcmd_error("alias failed\n");
    return rc;
}

static int do_unalias_cmd(int argc, char **argv)
{
    (void)argc;
    int rc;
    if (strcmp(argv[1], "pin") == 0)
        rc = hal_pin_alias(argv[2], NULL);
    else if (strcmp(argv[1], "param") == 0)
        rc = hal_param_alias(argv[2], NULL);
    else {
        halcmd_error("Unknown unalias type '%s'\n", argv[1]);
        return -EINVAL;
    }
    if (rc)
        halcmd_error("unalias failed\n");
    return rc;
}

/* ---- threads --------------------------------------------------------------------- */

static int do_addf_cmd(int argc, char **argv)
{
    int pos = -1;
    if (argc == 4) {
        char *end;
        long v = strtol(argv[3], &end, 0);
        if (*argv[3] == '\0' || *end != '\0' || v > 100000 || v < -100000) {
            halcmd_error("value '%s' invalid for position\n", argv[3]);
            return -EINVAL;
        }
        pos = (int)v;
    }
    int rc = hal_add_funct_to_thread(argv[1], argv[2], pos);
    if (rc)
        halcmd_error("addf failed\n");
    else
        halcmd_info("Function '%s' added to thread '%s'\n", argv[1], argv[2]);
    return rc;
}

static int do_delf_cmd(int argc, char **argv)
{
    (void)argc;
    int rc = hal_del_funct_from_thread(argv[1], argv[2]);
    if (rc)
        halcmd_error("delf failed\n");
    else
        halcmd_info("Function '%s' removed from thread '%s'\n", argv[1], argv[2]);
    return rc;
}

static int do_start_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    int rc = hal_start_threads();
    if (rc == 0)
        halcmd_info("Realtime threads started\n");
    return rc;
}

static int do_stop_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    int rc = hal_stop_threads();
    if (rc == 0)
        halcmd_info("Realtime threads stopped\n");
    return rc;
}

/* simrun DURATION: our extension (see docs/halcmd.md). */
static int do_simrun_cmd(int argc, char **argv)
{
    (void)argc;
    char *end;
    errno = 0;
    double v = strtod(argv[1], &end);
    double mult = 1;
    if (strcmp(end, "s") == 0)
        mult = 1e9;
    else if (strcmp(end, "ms") == 0)
        mult = 1e6;
    else if (strcmp(end, "us") == 0)
        mult = 1e3;
    else if (strcmp(end, "ns") == 0 || *end == '\0')
        mult = 1;
    else
        end = NULL;
    if (end == NULL || end == argv[1] || errno || v < 0 || v * mult > 9.2e18) {
        halcmd_error("simrun: bad duration '%s' (use e.g. 1000000, 10ms, 2s)\n", argv[1]);
        return -EINVAL;
    }
    if (!rtapi_is_simclock()) {
        halcmd_error("simrun: the session does not run on the simulated clock "
                     "(HAL_SIMCLOCK=1 or halrun -S)\n");
        return -EPERM;
    }
    char ns[32];
    snprintf(ns, sizeof(ns), "%lld", (long long)(v * mult + 0.5));
    const char *av[] = {"simrun", ns};
    int status = 0;
    char *msgs = NULL;
    int rc = rtapi_client_request(0, 2, av, &status, &msgs);
    print_rt_messages(msgs);
    free(msgs);
    if (rc == -ECONNREFUSED || rc == -ENOENT) {
        /* No realtime host: no threads, time still passes. */
        hal_priv_lock();
        hal_hdr->sim_time += (int64_t)(v * mult + 0.5);
        hal_priv_unlock();
        return 0;
    }
    if (rc != 0 || status != 0) {
        halcmd_error("simrun failed\n");
        return rc ? rc : status;
    }
    return 0;
}

/* ---- lock ----------------------------------------------------------------------- */

static int do_lock_cmd(int argc, char **argv)
{
    unsigned char l = HAL_LOCK_ALL;
    if (argc > 1) {
        if (strcmp(argv[1], "all") == 0)
            l = HAL_LOCK_ALL;
        else if (strcmp(argv[1], "tune") == 0)
            l = HAL_LOCK_TUNE;
        else if (strcmp(argv[1], "none") == 0)
            l = HAL_LOCK_NONE;
        else {
            halcmd_error("Unknown lock type '%s'\n", argv[1]);
            return -EINVAL;
        }
    }
    return hal_set_lock(l);
}

static int do_unlock_cmd(int argc, char **argv)
{
    unsigned char l = hal_get_lock();
    if (argc == 1 || strcmp(argv[1], "all") == 0)
        l = HAL_LOCK_NONE;
    else if (strcmp(argv[1], "tune") == 0)
        l &= (unsigned char)~HAL_LOCK_TUNE;
    else {
        halcmd_error("Unknown unlock type '%s'\n", argv[1]);
        return -EINVAL;
    }
    return hal_set_lock(l);
}

/* ---- misc ----------------------------------------------------------------------- */

static int do_source_cmd(int argc, char **argv)
{
    (void)argc;
    return halcmd_source(argv[1], 0);
}

static int do_echo_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    hc.echo = 1;
    return 0;
}

static int do_unecho_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    hc.echo = 0;
    halcmd_output("Echo off\n");
    return 0;
}

static int do_quit_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    hc.done = 1;
    return 0;
}

static int do_debug_cmd(int argc, char **argv)
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

static int do_print_cmd(int argc, char **argv)
{
    /* LinuxCNC 2.9 prints "(null)" when there is no message. */
    halcmd_error("HALCMD MSG: %s\n", argc > 1 ? argv[1] : "(null)");
    return 0;
}

static int do_setexact_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    hal_priv_lock();
    int have_threads = hal_hdr->thread_list != 0;
    if (!have_threads)
        hal_hdr->exact_for_test = 1;
    hal_priv_unlock();
    if (have_threads) {
        halcmd_error("HAL_LIB: Cannot run 'setexact' after a thread has been created\n");
        return -EINVAL;
    }
    /* Periods are used exactly anyway in this implementation; the flag is
     * kept for compatibility (and reported like LinuxCNC). */
    halcmd_error("Warning: HAL_LIB: HAL will pretend that the exact base period requested "
                 "is possible.\nThis mode is not suitable for running real hardware.\n");
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

static void open_error(int top, const char *path, int e)
{
    if (top) {
        /* -f FILE: LinuxCNC's message has no file:line prefix */
        if (!hc.very_quiet)
            fprintf(stderr, "Could not open hal file '%s': %s\n", path, strerror(e));
    } else {
        halcmd_error("Could not open hal file '%s': %s\n", path, strerror(e));
    }
}

int halcmd_source(const char *path, int top)
{
    FILE *f = fopen(path, "r");
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
