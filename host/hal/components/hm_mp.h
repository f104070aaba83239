/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm_mp.h - module-parameter declarations with the ABI of rtapi.h
 * (rtapi_info_{address,type,size,description}_<var>, looked up by
 * rtapi_app with dlsym).  rtapi.h's RTAPI_MP_* macros currently fail to
 * expand (their `type` parameter collides with a token they paste; see
 * host/hal/REQUESTS-h2.md), so h2's components declare their parameters
 * with these equivalents.
 */
#ifndef HM_MP_H
#define HM_MP_H

#include "rtapi.h"

#define HM_MP_DECLARE_(var_, typestr_, descr_)                                            \
    RTAPI_EXPORT __attribute__((used)) void *rtapi_info_address_##var_ = (void *)&(var_); \
    RTAPI_EXPORT __attribute__((used)) const char *rtapi_info_type_##var_ = typestr_;     \
    RTAPI_EXPORT __attribute__((used)) const char *rtapi_info_description_##var_ = descr_

#define HM_MP_ARRAY_DECLARE_(var_, typestr_, num_, descr_) \
    HM_MP_DECLARE_(var_, typestr_, descr_);                 \
    RTAPI_EXPORT __attribute__((used)) int rtapi_info_size_##var_ = (num_)

#define HM_MP_INT(var_, descr_) HM_MP_DECLARE_(var_, RTAPI_MP_TYPE_INT, descr_)
#define HM_MP_ARRAY_INT(var_, num_, descr_) \
    HM_MP_ARRAY_DECLARE_(var_, RTAPI_MP_TYPE_INT, num_, descr_)
#define HM_MP_ARRAY_STRING(var_, num_, descr_) \
    HM_MP_ARRAY_DECLARE_(var_, RTAPI_MP_TYPE_STRING, num_, descr_)

#endif /* HM_MP_H */
