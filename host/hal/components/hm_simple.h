/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm_simple.h - the module boilerplate shared by every component built on
 * hm_comp: the count= and names= module parameters, rtapi_app_main and
 * rtapi_app_exit.  Use once per module, after defining the descriptor:
 *
 *     static const hm_comp_desc_t desc = { ... };
 *     HM_SIMPLE_COMPONENT(desc, "description");
 */
#ifndef HM_SIMPLE_H
#define HM_SIMPLE_H

#include <stddef.h>

#include "hal.h"
#include "hm_comp.h"
#include "rtapi.h"

/* Module parameters and the component id are the only module-level state
 * (rtapi_app_exit needs the id); instance state lives in HAL memory. */
#define HM_SIMPLE_COMPONENT(desc_, description_)                                      \
    static int count;                                                                 \
    RTAPI_MP_INT(count, "number of instances (default 1)");                           \
    static char *names[HM_COMP_MAX_NAMES];                                            \
    RTAPI_MP_ARRAY_STRING(names, HM_COMP_MAX_NAMES, "names of instances");            \
    static int hm_comp_id_;                                                           \
    int rtapi_app_main(void) { return hm_comp_load(&(desc_), count, names, &hm_comp_id_); } \
    void rtapi_app_exit(void) { hal_exit(hm_comp_id_); }                              \
    MODULE_LICENSE("GPL");                                                            \
    MODULE_DESCRIPTION(description_)

#define HM_PIN(struct_, member_, type_, dir_, dflt_) \
    { #member_, type_, dir_, offsetof(struct_, member_), dflt_ }
#define HM_PIN_N(struct_, member_, name_, type_, dir_, dflt_) \
    { name_, type_, dir_, offsetof(struct_, member_), dflt_ }

#define HM_COUNT(arr_) ((int)(sizeof(arr_) / sizeof((arr_)[0])))

#endif /* HM_SIMPLE_H */
