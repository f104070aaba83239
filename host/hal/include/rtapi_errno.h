/* SPDX-License-Identifier: GPL-2.0-or-later */
/* rtapi_errno.h - errno values (EINVAL, ENOMEM, EBUSY, ...) for components. */
#ifndef HM_RTAPI_ERRNO_H
#define HM_RTAPI_ERRNO_H

#include <errno.h>

#endif /* HM_RTAPI_ERRNO_H */
