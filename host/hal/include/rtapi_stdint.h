/* SPDX-License-Identifier: GPL-2.0-or-later */
/* rtapi_stdint.h - fixed-width integers (uint32_t, ...) and their limits. */
#ifndef HM_RTAPI_STDINT_H
#define HM_RTAPI_STDINT_H

#include <stdint.h>

#endif /* HM_RTAPI_STDINT_H */
