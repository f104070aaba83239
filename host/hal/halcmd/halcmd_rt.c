/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_rt.c - realtime modules (loadrt, unloadrt) through rtapi_app,
 * with LinuxCNC 2.9's component id sequence, and simrun.
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

/* ---- loadrt / unloadrt ----------------------------------------------------- */

/* Component ids are printed by `show`, so they follow LinuxCNC 2.9's
 * sequence: its halcmd runs loadrt through a helper process that takes one
 * id, and re-registers its own component (new id) on every successful
 * loadrt after the first.  A failed loadrt that created nothing takes no
 * id.  ids_before() reserves, ids_after() settles. */
static int ids_before(void) { return halpr_reserve_ids(hc.loadrt_done > 0 ? 2 : 1); }

static void ids_after(int a, int ok)
{
    if (!ok) {
        halpr_release_ids(a, hc.loadrt_done > 0 ? 2 : 1);
        return;
    }
    if (hc.loadrt_done > 0 && halpr_comp_set_id(hc.comp_id, a + 1) == 0)
        hc.comp_id = a + 1;
    hc.loadrt_done++;
}

int do_loadrt_cmd(int argc, char **argv)
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

int unloadrt_all(void)
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

int do_unloadrt_cmd(int argc, char **argv)
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

/* simrun DURATION: our extension (see docs/halcmd.md). */
int do_simrun_cmd(int argc, char **argv)
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
        halpr_sim_advance((long long)(v * mult + 0.5));
        return 0;
    }
    if (rc != 0 || status != 0) {
        halcmd_error("simrun failed\n");
        return rc ? rc : status;
    }
    return 0;
}

