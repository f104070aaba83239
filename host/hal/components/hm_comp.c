/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm_comp.c - count=/names= handling and table-driven instance creation for
 * the simple realtime components.  See hm_comp.h.
 */
#include "hm_comp.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>

/* hal_export_funct() adds NAME.time, NAME.tmax and NAME.tmax-increased. */
#define FUNCT_EXTRA_SUFFIX ".tmax-increased"

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

int hm_comp_instance_names(const char *modname, const char *prefix, const char *count_name,
                           int count, int max_count, char *const *names, int max_names,
                           size_t longest_suffix, char (*out)[HAL_NAME_LEN + 1])
{
    int nnames = 0;
    while (nnames < max_names && names[nnames] != NULL && names[nnames][0] != '\0')
        nnames++;
    /* names=a,,b: an empty entry in the middle is a typo, not an end marker */
    for (int i = nnames; i < max_names; i++) {
        if (names[i] != NULL && names[i][0] != '\0') {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: names: entry %d is empty\n", modname,
                            nnames + 1);
            return -EINVAL;
        }
    }
    if (count != 0 && nnames > 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: %s= and names= are mutually exclusive\n",
                        modname, count_name);
        return -EINVAL;
    }
    if (nnames > 0) {
        for (int i = 0; i < nnames; i++) {
            const char *n = names[i];
            if (!name_is_valid(n)) {
                rtapi_print_msg(RTAPI_MSG_ERR,
                                "%s: ERROR: names: \"%s\" is not a valid HAL name "
                                "(empty, blank or unprintable characters)\n",
                                modname, n);
                return -EINVAL;
            }
            if (strlen(n) + longest_suffix > HAL_NAME_LEN) {
                rtapi_print_msg(RTAPI_MSG_ERR,
                                "%s: ERROR: names: \"%s\" too long: with its longest suffix "
                                "it needs %zu characters, HAL names have at most %d\n",
                                modname, n, strlen(n) + longest_suffix, HAL_NAME_LEN);
                return -EINVAL;
            }
            for (int j = 0; j < i; j++) {
                if (strcmp(names[j], n) == 0) {
                    rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: names: \"%s\" given twice\n",
                                    modname, n);
                    return -EINVAL;
                }
            }
            strcpy(out[i], n);
        }
        return nnames;
    }
    if (count < 0 || count > max_count) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: %s=%d out of range (1 to %d)\n", modname,
                        count_name, count, max_count);
        return -EINVAL;
    }
    if (count == 0)
        count = 1; /* LinuxCNC: count=0 or no count means one instance */
    for (int i = 0; i < count; i++)
        snprintf(out[i], HAL_NAME_LEN + 1, "%s.%d", prefix, i);
    if (strlen(out[count - 1]) + longest_suffix > HAL_NAME_LEN) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: %s=%d makes names longer than %d characters\n",
                        modname, count_name, count, HAL_NAME_LEN);
        return -EINVAL;
    }
    return count;
}

static size_t longest_suffix_of(const hm_comp_desc_t *d)
{
    size_t longest = 0;
    size_t fs = d->funct_suffix ? strlen(d->funct_suffix) + 1 : 0;
    longest = fs + strlen(FUNCT_EXTRA_SUFFIX);
    for (int i = 0; i < d->npins; i++)
        if (strlen(d->pins[i].suffix) + 1 > longest)
            longest = strlen(d->pins[i].suffix) + 1;
    for (int i = 0; i < d->nparams; i++)
        if (strlen(d->params[i].suffix) + 1 > longest)
            longest = strlen(d->params[i].suffix) + 1;
    return longest;
}

static void set_default(volatile void *p, hal_type_t type, double v)
{
    switch (type) {
    case HAL_BIT:
        *(hal_bit_t *)p = (v != 0.0);
        break;
    case HAL_FLOAT:
        *(hal_float_t *)p = v;
        break;
    case HAL_S32:
        *(hal_s32_t *)p = (rtapi_s32)v;
        break;
    case HAL_U32:
        *(hal_u32_t *)p = (rtapi_u32)v;
        break;
    case HAL_S64:
        *(hal_s64_t *)p = (rtapi_s64)v;
        break;
    case HAL_U64:
        *(hal_u64_t *)p = (rtapi_u64)v;
        break;
    default:
        break;
    }
}

static int create_instance(const hm_comp_desc_t *d, const char *iname, int comp_id)
{
    char *inst = hal_malloc((long)d->inst_size);
    if (inst == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: out of HAL memory for instance %s\n",
                        d->modname, iname);
        return -ENOMEM;
    }
    memset(inst, 0, d->inst_size);
    for (int i = 0; i < d->npins; i++) {
        const hm_item_t *it = &d->pins[i];
        void **slot = (void **)(inst + it->offset);
        int r = hal_pin_newf(it->type, (hal_pin_dir_t)it->dir, slot, comp_id, "%s.%s", iname,
                             it->suffix);
        if (r < 0)
            return r;
        set_default(*slot, it->type, it->dflt);
    }
    for (int i = 0; i < d->nparams; i++) {
        const hm_item_t *it = &d->params[i];
        volatile void *val = inst + it->offset;
        set_default(val, it->type, it->dflt);
        int r = hal_param_newf(it->type, (hal_param_dir_t)it->dir, val, comp_id, "%s.%s", iname,
                               it->suffix);
        if (r < 0)
            return r;
    }
    if (d->funct_suffix)
        return hal_export_functf(d->funct, inst, d->uses_fp, 0, comp_id, "%s.%s", iname,
                                 d->funct_suffix);
    return hal_export_functf(d->funct, inst, d->uses_fp, 0, comp_id, "%s", iname);
}

int hm_comp_load(const hm_comp_desc_t *d, int count, char *const *names, int *comp_id_out)
{
    return hm_comp_load_ex(d, "count", count, HM_COMP_MAX_COUNT, names, HM_COMP_MAX_NAMES,
                           comp_id_out);
}

int hm_comp_load_ex(const hm_comp_desc_t *d, const char *count_name, int count, int max_count,
                    char *const *names, int max_names, int *comp_id_out)
{
    char(*inames)[HAL_NAME_LEN + 1] =
        calloc((size_t)(max_count > max_names ? max_count : max_names), sizeof(*inames));
    if (inames == NULL)
        return -ENOMEM;
    int n = hm_comp_instance_names(d->modname, d->prefix, count_name, count, max_count, names,
                                   max_names, longest_suffix_of(d), inames);
    if (n < 0) {
        free(inames);
        return n;
    }
    int comp_id = hal_init(d->modname);
    if (comp_id < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: hal_init() failed: %d\n", d->modname,
                        comp_id);
        free(inames);
        return comp_id;
    }
    for (int i = 0; i < n; i++) {
        int r = create_instance(d, inames[i], comp_id);
        if (r < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: creating instance %s failed (%d), "
                            "nothing of %s was kept\n",
                            d->modname, inames[i], r, d->modname);
            hal_exit(comp_id);
            free(inames);
            return r;
        }
    }
    free(inames);
    hal_ready(comp_id);
    *comp_id_out = comp_id;
    return 0;
}
