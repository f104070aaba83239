/* SPDX-License-Identifier: GPL-2.0-or-later */
/* rtapi_ctype.h - character classes (isdigit, isspace, toupper, ...). */
#ifndef HM_RTAPI_CTYPE_H
#define HM_RTAPI_CTYPE_H

#include <ctype.h>

#endif /* HM_RTAPI_CTYPE_H */
