/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm_comp.h - shared plumbing for the simple realtime components (and2,
 * sum2, conv_*, ...): the LinuxCNC `count=` / `names=` instance
 * conventions, table-driven creation of pins and parameters with their
 * defaults, and all-or-nothing loading.
 *
 * A component describes its per-instance state as a C struct holding the
 * pin pointers and parameter values, and lists its pins and parameters in
 * tables that give each one's name suffix, type, direction, default and
 * offsetof() in that struct.  hm_comp_load() validates every module
 * parameter and every name that will be created *before* touching HAL, then
 * creates the instances; on any failure it calls hal_exit() so no pin,
 * parameter or function of the component is left behind.
 *
 * This file is compiled into each component module (hidden visibility), so
 * the helpers are private to each .so.
 */
#ifndef HM_COMP_H
#define HM_COMP_H

#include <stddef.h>

#include "hal.h"

/* The `names=` array size of every component built on this helper, and the
 * largest `count=` accepted (HAL memory would run out long before). */
#define HM_COMP_MAX_NAMES 256
#define HM_COMP_MAX_COUNT 1000

/* One pin or parameter of an instance.  For a pin, `dir` is HAL_IN, HAL_OUT
 * or HAL_IO and `offset` locates the hal_xxx_t* in the instance struct; for
 * a parameter `dir` is HAL_RO or HAL_RW and `offset` locates the hal_xxx_t
 * value itself.  `dflt` is stored after creation (0 for most). */
typedef struct {
    const char *suffix;
    hal_type_t type;
    int dir;
    size_t offset;
    double dflt;
} hm_item_t;

typedef struct {
    const char *modname;  /* hal_init name and error-message prefix: "conv_s32_u32" */
    const char *prefix;   /* default instance prefix: "conv-s32-u32" */
    size_t inst_size;     /* sizeof the per-instance struct */
    const hm_item_t *pins;
    int npins;
    const hm_item_t *params;
    int nparams;
    void (*funct)(void *inst, long period);
    int uses_fp;
    /* Function name suffix: NULL -> the function is named like the
     * instance ("and2.0"), "update" -> "siggen.0.update". */
    const char *funct_suffix;
} hm_comp_desc_t;

/* Load the component: count/names are the module parameters (names[] has
 * HM_COMP_MAX_NAMES entries, unset ones NULL).  Returns 0 or -errno after
 * printing an RTAPI_MSG_ERR line that says what was wrong.  *comp_id_out
 * receives the component id on success. */
int hm_comp_load(const hm_comp_desc_t *desc, int count, char *const *names, int *comp_id_out);
/* The same with another name and limit for the count parameter (siggen's
 * num_chan=) and another names[] size. */
int hm_comp_load_ex(const hm_comp_desc_t *desc, const char *count_name, int count, int max_count,
                    char *const *names, int max_names, int *comp_id_out);

/* Resolve count=/names= into a list of instance names without touching HAL
 * (also used by components with hand-written setup, like siggen).
 * `count_name` is the parameter's name in messages ("count", "num_chan").
 * On success returns the number of instances and fills out[i] (each
 * HAL_NAME_LEN + 1 bytes); on error prints why and returns -EINVAL.
 * `longest_suffix` is the length of the longest ".xxx" that will be
 * appended to an instance name, so too-long names are caught up front. */
int hm_comp_instance_names(const char *modname, const char *prefix, const char *count_name,
                           int count, int max_count, char *const *names, int max_names,
                           size_t longest_suffix, char (*out)[HAL_NAME_LEN + 1]);

#endif /* HM_COMP_H */
