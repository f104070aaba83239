/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcomp.h - the runtime that halcompile-generated components link
 * (libhalcomp.so): LinuxCNC's count= / names= / personality= instance
 * conventions, table-driven creation of pins, parameters and functions, and
 * all-or-nothing loading.  See docs/halcompile.md.
 *
 * Generated code describes each instance's pins and parameters in a table
 * (name, type, direction, array size, offset in the instance struct) and
 * provides an `export` function that allocates one instance, runs the
 * component's EXTRA_SETUP, works out which conditional items exist and how
 * big personality-sized arrays are, and calls halcomp_make_items() and
 * halcomp_make_functs().  halcomp_load() checks every module parameter and
 * every name that will be created before it touches HAL, then creates the
 * instances; on any failure it runs EXTRA_CLEANUP and hal_exit() so nothing
 * of the component is left behind.
 *
 * Hand-written components may use it too (sampler, streamer, threads do
 * not need it).
 */
#ifndef HALCOMP_H
#define HALCOMP_H

#include <stddef.h>

#include "hal.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Sizes of the names= and personality= module parameter arrays (LinuxCNC
 * 2.9 accepts 64 personality values; instance i uses personality[i % 64])
 * and the largest count= accepted (HAL memory runs out long before). */
#define HALCOMP_MAX_NAMES 1000
#define HALCOMP_MAX_PERSONALITY 64
#define HALCOMP_MAX_COUNT 1000

/* One pin or parameter of an instance.  For a pin `dir` is HAL_IN, HAL_OUT
 * or HAL_IO and `offset` locates the hal_xxx_t * (of an array: the first of
 * `maxsize` pointers) in the instance struct; for a parameter `dir` is
 * HAL_RO or HAL_RW and `offset` locates the value (or the first of
 * `maxsize`).  `name` is what follows "PREFIX."; in an array the one block
 * of '#' is replaced by the index, zero-padded to the number of '#'. */
typedef struct {
    const char *name;
    hal_type_t type;
    int dir;
    int is_param;
    int maxsize;   /* 0: not an array */
    size_t offset; /* of the first element */
    size_t stride; /* bytes from one array element to the next */
} halcomp_item_t;

/* One realtime function per instance: named PREFIX.NAME, or PREFIX when
 * name is "" (LinuxCNC's `function _`). */
typedef struct {
    const char *name;
    void (*funct)(void *inst, long period);
    int uses_fp;
} halcomp_funct_t;

typedef struct {
    const char *modname;  /* hal_init name and message prefix: "hal_loop" */
    const char *prefix;   /* numbered instances: PREFIX.N ("loop.0"); singleton: PREFIX */
    int singleton;
    int default_count;    /* count when neither count= nor names= is given */
    int (*get_count)(void); /* option count_function: the count, or NULL */
    int has_names;        /* names= exists (not with singleton / count_function) */
    int has_personality;
    /* Longest ".suffix" appended to an instance name (pins, params,
     * function names with their ".tmax"; HAL cuts ".tmax-increased" to
     * fit, as LinuxCNC does), for up-front checks. */
    size_t longest_suffix;
    int (*export_inst)(char *prefix, long extra_arg, long personality);
    void (*extra_cleanup)(void); /* or NULL */
} halcomp_desc_t;

/* The module parameters as given on the loadrt line.  A component with
 * `option rtapi_app no` may load itself through HALCOMP_LOAD(&args) with
 * another count parameter (siggen's num_chan=): count_name, max_count and
 * max_names then replace "count", HALCOMP_MAX_COUNT and HALCOMP_MAX_NAMES
 * (0/NULL: the defaults; larger values are limited to them). */
typedef struct {
    int count;
    char *const *names;     /* max_names entries, unset ones NULL */
    const int *personality; /* HALCOMP_MAX_PERSONALITY entries */
    const char *count_name;
    int max_count;
    int max_names;
} halcomp_args_t;

/* Load the component: resolve the instances, hal_init(), export each one,
 * hal_ready().  *comp_id is set right after hal_init() (export_inst uses
 * it).  Returns 0 or -errno after printing an RTAPI_MSG_ERR line that says
 * what was wrong; on failure nothing of the component remains. */
int halcomp_load(const halcomp_desc_t *desc, const halcomp_args_t *args, int *comp_id);

/* Resolve count=/names= into instance names without touching HAL (for
 * hand-written components too).  `count_name` is the count parameter's
 * name in messages ("count", "num_chan").  Fills out[i] (HAL_NAME_LEN + 1
 * bytes each) and returns the number of instances, or -EINVAL after
 * printing why. */
int halcomp_instance_names(const char *modname, const char *prefix, const char *count_name,
                           int count, int max_count, char *const *names, int max_names,
                           size_t longest_suffix, char (*out)[HAL_NAME_LEN + 1]);

/* hal_malloc + zero, with a message naming the instance on failure. */
void *halcomp_alloc(const char *modname, const char *prefix, size_t size);

/* Create the items of one instance.  sizes[i] is how many of item i exist
 * for this instance: 0 (its `if` condition is false, or a personality size
 * of 0), 1 for a scalar, the array length for an array (more than maxsize
 * fails with -ENOSPC). */
int halcomp_make_items(int comp_id, const char *prefix, void *inst, const halcomp_item_t *items,
                       int nitems, const int *sizes);
int halcomp_make_functs(int comp_id, const char *prefix, void *inst,
                        const halcomp_funct_t *functs, int nfuncts);

/* A userspace component's main(): argv handling of count=N / names=a,b /
 * personality=p,q (LinuxCNC loadusr style, e.g. `loadusr rand count=2`).
 * Parses the arguments it knows into *args (storage in `names_buf` and
 * `pers_buf`, sized HALCOMP_MAX_NAMES / HALCOMP_MAX_PERSONALITY) and
 * removes them from argv.  Returns 0 or -EINVAL after printing why. */
int halcomp_user_args(const char *modname, int *argc, char **argv, halcomp_args_t *args,
                      char **names_buf, int *pers_buf);

#ifdef __cplusplus
}
#endif

#endif /* HALCOMP_H */
