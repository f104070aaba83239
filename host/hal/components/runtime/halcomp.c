/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcomp.c - libhalcomp: instance handling and table-driven creation of
 * pins, parameters and functions for halcompile-generated components.
 * See halcomp.h.
 */
#include "halcomp.h"

#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rtapi.h"

#define API __attribute__((visibility("default")))

static int name_is_valid(const char *s)
{
    if (*s == '\0')
        return 0;
    for (; *s; s++) {
        if (isspace((unsigned char)*s) || !isprint((unsigned char)*s))
            return 0;
    }
    return 1;
}

static int count_names(const char *modname, char *const *names, int max_names)
{
    int n = 0;
    while (n < max_names && names[n] != NULL && names[n][0] != '\0')
        n++;
    /* names=a,,b: an empty entry in the middle is a typo, not an end marker
     * (LinuxCNC 2.9's message; its realtime modules then make a nameless
     * instance, its userspace ones refuse) */
    (void)modname;
    for (int i = n; i < max_names; i++) {
        if (names[i] != NULL && names[i][0] != '\0') {
            rtapi_print_msg(RTAPI_MSG_ERR, "names[%d] is invalid (empty string)\n", n);
            return -EINVAL;
        }
    }
    return n;
}

static int check_names(const char *modname, char *const *names, int n, size_t longest_suffix,
                       char (*out)[HAL_NAME_LEN + 1])
{
    for (int i = 0; i < n; i++) {
        const char *s = names[i];
        if (!name_is_valid(s)) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "%s: ERROR: names: \"%s\" is not a valid HAL name "
                            "(empty, blank or unprintable characters)\n",
                            modname, s);
            return -EINVAL;
        }
        if (strlen(s) + longest_suffix > HAL_NAME_LEN) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "%s: ERROR: names: \"%s\" too long: with its longest suffix "
                            "it needs %zu characters, HAL names have at most %d\n",
                            modname, s, strlen(s) + longest_suffix, HAL_NAME_LEN);
            return -EINVAL;
        }
        for (int j = 0; j < i; j++) {
            if (strcmp(names[j], s) == 0) {
                rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: names: \"%s\" given twice\n",
                                modname, s);
                return -EINVAL;
            }
        }
        strcpy(out[i], s);
    }
    return n;
}

API int halcomp_instance_names(const char *modname, const char *prefix, const char *count_name,
                               int count, int max_count, char *const *names, int max_names,
                               size_t longest_suffix, char (*out)[HAL_NAME_LEN + 1])
{
    int nnames = names ? count_names(modname, names, max_names) : 0;
    if (nnames < 0)
        return nnames;
    if (count != 0 && nnames > 0) {
        /* LinuxCNC 2.9 prints exactly this line */
        rtapi_print_msg(RTAPI_MSG_ERR, "%s= and names= are mutually exclusive\n", count_name);
        return -EINVAL;
    }
    if (nnames > 0)
        return check_names(modname, names, nnames, longest_suffix, out);
    if (count < 0 || count > max_count) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: %s=%d out of range (1 to %d)\n", modname,
                        count_name, count, max_count);
        return -EINVAL;
    }
    if (count == 0)
        return 0;
    for (int i = 0; i < count; i++)
        snprintf(out[i], HAL_NAME_LEN + 1, "%s.%d", prefix, i);
    if (strlen(prefix) + 1 + (size_t)snprintf(NULL, 0, "%d", count - 1) + longest_suffix >
        HAL_NAME_LEN) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: %s=%d makes names longer than %d characters\n",
                        modname, count_name, count, HAL_NAME_LEN);
        return -EINVAL;
    }
    return count;
}

/* The instance names of this load, or a negative errno. */
static int resolve(const halcomp_desc_t *d, const halcomp_args_t *a,
                   char (*out)[HAL_NAME_LEN + 1])
{
    if (d->singleton) {
        if (strlen(d->prefix) + d->longest_suffix > HAL_NAME_LEN) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: names longer than %d characters\n",
                            d->modname, HAL_NAME_LEN);
            return -EINVAL;
        }
        snprintf(out[0], HAL_NAME_LEN + 1, "%s", d->prefix);
        return 1;
    }
    if (d->get_count) {
        int n = d->get_count();
        if (n < 0 || n > HALCOMP_MAX_COUNT) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: get_count() returned %d (0 to %d)\n",
                            d->modname, n, HALCOMP_MAX_COUNT);
            return -EINVAL;
        }
        return n == 0 ? 0
                      : halcomp_instance_names(d->modname, d->prefix, "count", n,
                                               HALCOMP_MAX_COUNT, NULL, 0, d->longest_suffix,
                                               out);
    }
    const char *cname = a->count_name ? a->count_name : "count";
    /* never more than the instance table of halcomp_load holds */
    int max_count = a->max_count > 0 && a->max_count < HALCOMP_MAX_COUNT ? a->max_count
                                                                         : HALCOMP_MAX_COUNT;
    int max_names = a->max_names > 0 && a->max_names < HALCOMP_MAX_NAMES ? a->max_names
                                                                         : HALCOMP_MAX_NAMES;
    int count = a->count;
    if (count == 0 && !(d->has_names && a->names && a->names[0] && a->names[0][0]))
        count = d->default_count;
    if (count == 0 && !d->has_names)
        return 0;
    return halcomp_instance_names(d->modname, d->prefix, cname, count, max_count,
                                  d->has_names ? a->names : NULL, max_names, d->longest_suffix,
                                  out);
}

API int halcomp_load(const halcomp_desc_t *d, const halcomp_args_t *a, int *comp_id)
{
    char(*inames)[HAL_NAME_LEN + 1] = calloc(HALCOMP_MAX_COUNT + 1, sizeof(*inames));
    if (inames == NULL)
        return -ENOMEM;
    int r = 0;
    int n = resolve(d, a, inames);
    if (n < 0) {
        r = n;
        goto out_free;
    }
    int id = hal_init(d->modname);
    if (id < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: hal_init() failed: %d\n", d->modname, id);
        r = id;
        goto out_free;
    }
    *comp_id = id;
    for (int i = 0; i < n; i++) {
        long pers = 0;
        if (d->has_personality && a->personality)
            pers = a->personality[i % HALCOMP_MAX_PERSONALITY];
        r = d->export_inst(inames[i], i, pers);
        /* What failed was printed where it failed (the HAL call, the
         * size check, EXTRA_SETUP); rtapi_app reports the return value,
         * as LinuxCNC's does. */
        if (r != 0)
            goto out_exit;
    }
    hal_ready(id);
    free(inames);
    return 0;

out_exit:
    if (d->extra_cleanup)
        d->extra_cleanup();
    hal_exit(id);
out_free:
    free(inames);
    return r < 0 ? r : -EINVAL;
}

API void *halcomp_alloc(const char *modname, const char *prefix, size_t size)
{
    void *p = hal_malloc((long)size);
    if (p == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: out of HAL memory for instance %s\n",
                        modname, prefix);
        return NULL;
    }
    memset(p, 0, size);
    return p;
}

/* "PREFIX.NAME" with the '#' block of NAME replaced by `index`. */
static void item_name(char *buf, size_t len, const char *prefix, const char *name, int index)
{
    const char *h = strchr(name, '#');
    if (h == NULL || index < 0) {
        snprintf(buf, len, "%s.%s", prefix, name);
        return;
    }
    int width = (int)strspn(h, "#");
    snprintf(buf, len, "%s.%.*s%0*d%s", prefix, (int)(h - name), name, width, index, h + width);
}

static int make_one(int comp_id, const halcomp_item_t *it, char *inst, int j, const char *name)
{
    char *at = inst + it->offset + (size_t)j * it->stride;
    if (it->is_param)
        return hal_param_new(name, it->type, (hal_param_dir_t)it->dir, (volatile void *)at,
                             comp_id);
    return hal_pin_new(name, it->type, (hal_pin_dir_t)it->dir, (void **)at, comp_id);
}

API int halcomp_make_items(int comp_id, const char *prefix, void *inst, const halcomp_item_t *items,
                           int nitems, const int *sizes)
{
    char name[HAL_NAME_LEN + 16];
    for (int i = 0; i < nitems; i++) {
        const halcomp_item_t *it = &items[i];
        int n = sizes[i];
        if (it->maxsize > 0 && n > it->maxsize) {
            /* LinuxCNC 2.9's wording */
            rtapi_print_msg(RTAPI_MSG_ERR, "%s %s: Requested size %d exceeds max size %d\n",
                            it->is_param ? "Param" : "Pin", it->name, n, it->maxsize);
            return -ENOSPC;
        }
        if (n < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s %s: Requested size %d is negative\n",
                            it->is_param ? "Param" : "Pin", it->name, n);
            return -EINVAL;
        }
        for (int j = 0; j < n; j++) {
            item_name(name, sizeof(name), prefix, it->name, it->maxsize > 0 ? j : -1);
            if (strlen(name) > HAL_NAME_LEN) {
                rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: name '%s' longer than %d characters\n",
                                name, HAL_NAME_LEN);
                return -EINVAL;
            }
            int r = make_one(comp_id, it, inst, j, name);
            if (r < 0)
                return r;
        }
    }
    return 0;
}

API int halcomp_make_functs(int comp_id, const char *prefix, void *inst,
                            const halcomp_funct_t *functs, int nfuncts)
{
    for (int i = 0; i < nfuncts; i++) {
        const halcomp_funct_t *f = &functs[i];
        int r;
        if (f->name[0] == '\0')
            r = hal_export_functf(f->funct, inst, f->uses_fp, 0, comp_id, "%s", prefix);
        else
            r = hal_export_functf(f->funct, inst, f->uses_fp, 0, comp_id, "%s.%s", prefix,
                                  f->name);
        if (r < 0)
            return r;
    }
    return 0;
}

/* Split "a,b,c" into buf (at most max entries); returns the count or -1. */
static int split_list(char *s, char **buf, int max)
{
    int n = 0;
    for (char *tok = s;; n++) {
        char *comma = strchr(tok, ',');
        if (n >= max)
            return -1;
        buf[n] = tok;
        if (comma == NULL)
            return n + 1;
        *comma = '\0';
        tok = comma + 1;
    }
}

static int parse_int(const char *s, long *out)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 0);
    if (errno != 0 || end == s || *end != '\0')
        return -1;
    *out = v;
    return 0;
}

static int user_arg(const char *modname, char *arg, halcomp_args_t *a, char **names_buf,
                    int *pers_buf)
{
    long v;
    if (strncmp(arg, "count=", 6) == 0) {
        if (parse_int(arg + 6, &v) < 0 || v < 0 || v > HALCOMP_MAX_COUNT) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: bad count '%s' (0 to %d)\n", modname,
                            arg + 6, HALCOMP_MAX_COUNT);
            return -EINVAL;
        }
        a->count = (int)v;
        return 1;
    }
    if (strncmp(arg, "names=", 6) == 0) {
        if (split_list(arg + 6, names_buf, HALCOMP_MAX_NAMES) < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: names: more than %d names\n", modname,
                            HALCOMP_MAX_NAMES);
            return -EINVAL;
        }
        return 1;
    }
    if (strncmp(arg, "personality=", 12) == 0) {
        char *items[HALCOMP_MAX_PERSONALITY];
        int n = split_list(arg + 12, items, HALCOMP_MAX_PERSONALITY);
        if (n < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: personality: more than %d values\n",
                            modname, HALCOMP_MAX_PERSONALITY);
            return -EINVAL;
        }
        for (int i = 0; i < n; i++) {
            if (parse_int(items[i], &v) < 0) {
                rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: personality: '%s' is not a number\n",
                                modname, items[i]);
                return -EINVAL;
            }
            pers_buf[i] = (int)v;
        }
        return 1;
    }
    return 0;
}

API int halcomp_user_args(const char *modname, int *argc, char **argv, halcomp_args_t *args,
                          char **names_buf, int *pers_buf)
{
    int out = 1;
    args->count = 0;
    args->names = names_buf;
    args->personality = pers_buf;
    for (int i = 1; i < *argc; i++) {
        int r = user_arg(modname, argv[i], args, names_buf, pers_buf);
        if (r < 0)
            return r;
        if (r == 0)
            argv[out++] = argv[i];
    }
    argv[out] = NULL;
    *argc = out;
    return 0;
}
