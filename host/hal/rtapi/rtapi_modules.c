/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_modules.c - realtime modules in rtapi_app: find NAME.so, set its
 * module parameters, run rtapi_app_main, and on unload take its functions
 * out of the threads before rtapi_app_exit and dlclose.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "rtapi_app.h"

typedef struct module {
    struct module *next;
    char name[HAL_NAME_LEN + 1];
    void *handle;
    int ncomps;
    int comp_ids[64];
    char **strings; /* string parameter values given to the module */
    int nstrings;
} module_t;

static void free_strings(module_t *m)
{
    for (int i = 0; i < m->nstrings; i++)
        free(m->strings[i]);
    free(m->strings);
    m->strings = NULL;
    m->nstrings = 0;
}

static module_t *modules;

/* Look for NAME.so in each directory of a colon-separated list. */
static int search_dirs(const char *list, const char *name, char *path, size_t len)
{
    if (list == NULL || *list == '\0')
        return -ENOENT;
    char *dirs = strdup(list), *save = NULL;
    if (dirs == NULL)
        return -ENOMEM;
    int rc = -ENOENT;
    for (char *d = strtok_r(dirs, ":", &save); d && rc != 0; d = strtok_r(NULL, ":", &save)) {
        if ((size_t)snprintf(path, len, "%s/%s.so", d, name) < len && access(path, R_OK) == 0)
            rc = 0;
    }
    free(dirs);
    return rc;
}

/* The component search path (docs/rtapi.md): $HAL_RTLIB_PATH (and its
 * older name $HAL_RTLIB_DIR), the user folder
 * $HOME/.local/lib/hm2stack/rtlib, then the build's lib/rtlib.  Only a
 * plain name is looked up, so nothing outside these folders loads. */
static int find_module_file(const char *name, char *path, size_t len)
{
    if (search_dirs(getenv("HAL_RTLIB_PATH"), name, path, len) == 0 ||
        search_dirs(getenv("HAL_RTLIB_DIR"), name, path, len) == 0)
        return 0;
    const char *home = getenv("HOME");
    if (home != NULL && home[0] == '/') {
        char user[PATH_MAX];
        if ((size_t)snprintf(user, sizeof(user), "%s/.local/lib/hm2stack/rtlib", home) <
                sizeof(user) &&
            search_dirs(user, name, path, len) == 0)
            return 0;
    }
    char self[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", self, sizeof(self) - 1);
    if (n > 0) {
        self[n] = '\0';
        char *slash = strrchr(self, '/');
        if (slash) {
            *slash = '\0';
            if ((size_t)snprintf(path, len, "%s/../lib/rtlib/%s.so", self, name) < len &&
                access(path, R_OK) == 0)
                return 0;
        }
    }
    return -ENOENT;
}

/* A module name is a plain file name: no directory, no way out of the
 * search path. */
static int check_module_name(const char *name)
{
    if (name[0] == '\0' || strchr(name, '/') != NULL || strstr(name, "..") != NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "%s: refused: a module name must not contain '/' or '..' (modules load "
                        "only from the component search path, see docs/rtapi.md)\n",
                        name);
        return -EINVAL;
    }
    if (strlen(name) > HAL_NAME_LEN) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: module name too long (at most %d characters)\n",
                        name, HAL_NAME_LEN);
        return -EINVAL;
    }
    return 0;
}

int rtapi_parse_long(const char *s, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 0);
    if (*s == '\0' || *end != '\0' || errno == ERANGE)
        return -EINVAL;
    *out = v;
    return 0;
}

/* Set one module parameter key=value; messages as LinuxCNC's rtapi_app. */
static int set_param(void *handle, const char *arg, module_t *m)
{
    const char *eq = strchr(arg, '=');
    char key[128];
    if (eq == NULL || eq == arg || (size_t)(eq - arg) >= sizeof(key)) {
        rtapi_print_msg(RTAPI_MSG_ERR, "Unknown parameter `%s'\n", arg);
        return -EINVAL;
    }
    memcpy(key, arg, (size_t)(eq - arg));
    key[eq - arg] = '\0';
    const char *value = eq + 1;
    char sym[192];
    snprintf(sym, sizeof(sym), "rtapi_info_address_%s", key);
    void **addrp = dlsym(handle, sym);
    snprintf(sym, sizeof(sym), "rtapi_info_type_%s", key);
    const char **typep = dlsym(handle, sym);
    if (addrp == NULL || typep == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "Unknown parameter `%s'\n", arg);
        return -EINVAL;
    }
    snprintf(sym, sizeof(sym), "rtapi_info_size_%s", key);
    int *sizep = dlsym(handle, sym);
    int count = sizep ? *sizep : 1;
    int is_array = sizep != NULL;
    char type = (*typep)[0];
    /* Parse everything first so a bad element changes nothing. */
    char *copy = strdup(value);
    if (copy == NULL)
        return -ENOMEM;
    /* halcmd passes config="a b,c d" with its quotes; LinuxCNC's halcmd
     * drops them before the module sees the value, so arrays split into
     * "a b" and "c d", not "\"a b" and "c d\"". */
    size_t vlen = strlen(copy);
    if (vlen >= 2 && copy[0] == '"' && copy[vlen - 1] == '"') {
        memmove(copy, copy + 1, vlen - 2);
        copy[vlen - 2] = '\0';
    }
    char *items[1024];
    int nitems = 0;
    if (is_array) {
        char *p = copy;
        for (;;) {
            if (nitems >= count || nitems >= 1024) {
                rtapi_print_msg(RTAPI_MSG_ERR,
                                "Too many values for parameter `%s' (at most %d)\n", arg,
                                count);
                free(copy);
                return -EINVAL;
            }
            items[nitems++] = p;
            char *comma = strchr(p, ',');
            if (comma == NULL)
                break;
            *comma = '\0';
            p = comma + 1;
        }
    } else {
        items[nitems++] = copy;
    }
    long lv[1024];
    for (int i = 0; i < nitems; i++) {
        if (type == 'i' || type == 'l') {
            if (rtapi_parse_long(items[i], &lv[i]) != 0 ||
                (type == 'i' && (lv[i] < INT_MIN || lv[i] > INT_MAX))) {
                rtapi_print_msg(RTAPI_MSG_ERR, "`%s' invalid for parameter `%s'\n", items[i],
                                arg);
                free(copy);
                return -EINVAL;
            }
        } else if (type != 's') {
            rtapi_print_msg(RTAPI_MSG_ERR, "parameter `%s' has unknown type `%s'\n", key,
                            *typep);
            free(copy);
            return -EINVAL;
        }
    }
    void *addr = *addrp;
    for (int i = 0; i < nitems; i++) {
        if (type == 'i')
            ((int *)addr)[i] = (int)lv[i];
        else if (type == 'l')
            ((long *)addr)[i] = lv[i];
        else {
            /* The string lives as long as the module is loaded. */
            char *s = strdup(items[i]);
            char **v = realloc(m->strings, sizeof(char *) * (size_t)(m->nstrings + 1));
            if (s == NULL || v == NULL) {
                free(s);
                if (v != NULL)
                    m->strings = v;
                free(copy);
                return -ENOMEM;
            }
            m->strings = v;
            m->strings[m->nstrings++] = s;
            ((char **)addr)[i] = s;
        }
    }
    free(copy);
    return 0;
}

static int comp_ids_snapshot(int *ids, int max)
{
    int n = 0;
    hal_priv_lock();
    for (hal_off_t off = hal_hdr->comp_list; off; off = ((hal_comp_t *)SHMPTR(off))->next)
        if (n < max)
            ids[n++] = ((hal_comp_t *)SHMPTR(off))->id;
    hal_priv_unlock();
    return n;
}

int rtapi_do_load(int argc, char **argv)
{
    if (argc < 2)
        return -EINVAL;
    const char *name = argv[1];
    for (module_t *m = modules; m; m = m->next)
        if (strcmp(m->name, name) == 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: already exists\n", name);
            return -EEXIST;
        }
    int rc0 = check_module_name(name);
    if (rc0 != 0)
        return rc0;
    char path[PATH_MAX];
    if (find_module_file(name, path, sizeof(path)) != 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: dlopen: %s.so: cannot open shared object file: "
                        "No such file or directory\n", name, name);
        return -ENOENT;
    }
    void *h = dlopen(path, RTLD_NOW | RTLD_GLOBAL);
    if (h == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: dlopen: %s\n", name, dlerror());
        return -ENOENT;
    }
    int (*app_main)(void) = (int (*)(void))dlsym(h, "rtapi_app_main");
    if (app_main == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: dlsym: %s\n", name, dlerror());
        dlclose(h);
        return -ENOENT;
    }
    module_t *m = calloc(1, sizeof(*m));
    if (m == NULL) {
        dlclose(h);
        return -ENOMEM;
    }
    for (int i = 2; i < argc; i++) {
        if (set_param(h, argv[i], m) != 0) {
            dlclose(h);
            free_strings(m);
            free(m);
            return -EINVAL;
        }
    }
    int before[1024];
    int nbefore = comp_ids_snapshot(before, 1024);
    int rc = app_main();
    if (rc < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: rtapi_app_main: %s (%d)\n", name, strerror(-rc), rc);
        /* Components the failed module left behind go with it. */
        int after[1024];
        int nafter = comp_ids_snapshot(after, 1024);
        for (int i = 0; i < nafter; i++) {
            int found = 0;
            for (int j = 0; j < nbefore; j++)
                if (before[j] == after[i])
                    found = 1;
            if (!found)
                halpr_comp_delete(after[i]);
        }
        __atomic_add_fetch(&hal_hdr->sim_abort, 1, __ATOMIC_RELEASE);
        rtapi_quiesce();
        dlclose(h);
        free_strings(m);
        free(m);
        return rc;
    }
    int after[1024];
    int nafter = comp_ids_snapshot(after, 1024);
    for (int i = 0; i < nafter && m->ncomps < 64; i++) {
        int found = 0;
        for (int j = 0; j < nbefore; j++)
            if (before[j] == after[i])
                found = 1;
        if (!found)
            m->comp_ids[m->ncomps++] = after[i];
    }
    snprintf(m->name, sizeof(m->name), "%s", name);
    m->handle = h;
    m->next = modules;
    modules = m;
    /* The loadrt arguments, for `save`. */
    char args[HAL_ARGS_LEN];
    args[0] = '\0';
    size_t used = 0;
    for (int i = 2; i < argc; i++) {
        int n = snprintf(args + used, sizeof(args) - used, "%s ", argv[i]);
        if (n < 0 || (size_t)n >= sizeof(args) - used)
            break;
        used += (size_t)n;
    }
    halpr_set_insmod_args(name, args);
    return 0;
}

static void remove_functs_of(module_t *m)
{
    hal_priv_lock();
    for (hal_off_t toff = hal_hdr->thread_list; toff;) {
        hal_thread_t *t = SHMPTR(toff);
        for (hal_off_t off = t->funct_list; off;) {
            hal_funct_entry_t *e = SHMPTR(off);
            off = e->next;
            hal_funct_t *f = SHMPTR(e->funct);
            hal_comp_t *c = SHMPTR(f->owner);
            for (int i = 0; i < m->ncomps; i++)
                if (c->id == m->comp_ids[i]) {
                    char fn[HAL_NAME_LEN + 1], tn[HAL_NAME_LEN + 1];
                    snprintf(fn, sizeof(fn), "%s", f->name);
                    snprintf(tn, sizeof(tn), "%s", t->name);
                    hal_priv_unlock();
                    hal_del_funct_from_thread(fn, tn);
                    hal_priv_lock();
                    off = t->funct_list; /* list changed: rescan */
                    break;
                }
        }
        toff = t->next;
    }
    hal_priv_unlock();
}

static int unload_module(module_t *m)
{
    /* Functions leave the threads before the module's exit code runs,
     * and the code stays mapped until no period is still inside it. */
    remove_functs_of(m);
    /* A function waiting in rtapi_sim_yield() for a peer gives up now. */
    __atomic_add_fetch(&hal_hdr->sim_abort, 1, __ATOMIC_RELEASE);
    rtapi_quiesce();
    void (*app_exit)(void) = (void (*)(void))dlsym(m->handle, "rtapi_app_exit");
    if (app_exit != NULL)
        app_exit();
    for (int i = 0; i < m->ncomps; i++)
        halpr_comp_delete(m->comp_ids[i]); /* what the module forgot */
    rtapi_quiesce();
    dlclose(m->handle);
    module_t **pp = &modules;
    while (*pp != m)
        pp = &(*pp)->next;
    *pp = m->next;
    free_strings(m);
    free(m);
    return 0;
}

int rtapi_do_unload(int argc, char **argv)
{
    if (argc < 2)
        return -EINVAL;
    for (module_t *m = modules; m; m = m->next)
        if (strcmp(m->name, argv[1]) == 0)
            return unload_module(m);
    rtapi_print_msg(RTAPI_MSG_ERR, "%s: not loaded\n", argv[1]);
    return -ENOENT;
}

void rtapi_unload_all(void)
{
    while (modules != NULL)
        unload_module(modules);
}

int rtapi_modules_loaded(void) { return modules != NULL; }

char *rtapi_module_list(void)
{
    size_t cap = 16;
    for (module_t *m = modules; m; m = m->next)
        cap += strlen(m->name) + 1;
    char *s = calloc(1, cap);
    if (s == NULL)
        return NULL;
    for (module_t *m = modules; m; m = m->next) {
        strcat(s, m->name);
        strcat(s, "\n");
    }
    return s;
}
