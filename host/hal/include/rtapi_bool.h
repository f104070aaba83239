/* SPDX-License-Identifier: GPL-2.0-or-later */
/* rtapi_bool.h - bool, true, false. */
#ifndef HM_RTAPI_BOOL_H
#define HM_RTAPI_BOOL_H

#include <stdbool.h>

#endif /* HM_RTAPI_BOOL_H */
