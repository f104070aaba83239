/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * rtapi_app.h - what a LinuxCNC component includes for rtapi_app_main() and
 * rtapi_app_exit(); both are declared in rtapi.h here.
 */
#ifndef HM_RTAPI_APP_H
#define HM_RTAPI_APP_H

#include "rtapi.h"

#endif /* HM_RTAPI_APP_H */
