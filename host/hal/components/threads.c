/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * threads - create up to three HAL threads (see docs/threads.md).
 *
 *   loadrt threads name1=servo period1=1000000 [fp1=1] name2=... name3=...
 *
 * Thread N is created when periodN is not 0; name1 defaults to "thread1"
 * with a 1 ms period.  Threads are created in the order 1, 2, 3, and as in
 * LinuxCNC the first thread fixes the clock period: later threads may not be
 * faster than it and are rounded to a multiple of it.  On any failure the
 * threads created so far are deleted again, so a failed loadrt leaves
 * nothing behind.
 */
#include <errno.h>

#include "hal.h"
#include "rtapi.h"

MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("creates HAL threads");
MODULE_LICENSE("GPL");

static char *name1 = "thread1";
RTAPI_MP_STRING(name1, "name of thread 1");
static long period1 = 1000000;
RTAPI_MP_LONG(period1, "period of thread 1 (ns)");
static int fp1 = 1;
RTAPI_MP_INT(fp1, "thread 1 uses floating point");
static char *name2 = "thread2";
RTAPI_MP_STRING(name2, "name of thread 2");
static long period2 = 0;
RTAPI_MP_LONG(period2, "period of thread 2 (ns)");
static int fp2 = 1;
RTAPI_MP_INT(fp2, "thread 2 uses floating point");
static char *name3 = "thread3";
RTAPI_MP_STRING(name3, "name of thread 3");
static long period3 = 0;
RTAPI_MP_LONG(period3, "period of thread 3 (ns)");
static int fp3 = 1;
RTAPI_MP_INT(fp3, "thread 3 uses floating point");

/* Module parameters are the one allowed global state; the component id is
 * needed again in rtapi_app_exit. */
static int comp_id;

static void delete_created(int upto)
{
    const char *names[3] = {name1, name2, name3};
    const long periods[3] = {period1, period2, period3};
    for (int i = upto - 1; i >= 0; i--)
        if (periods[i] != 0)
            hal_thread_delete(names[i]);
}

int rtapi_app_main(void)
{
    const char *names[3] = {name1, name2, name3};
    const long periods[3] = {period1, period2, period3};
    const int fps[3] = {fp1, fp2, fp3};
    for (int i = 0; i < 3; i++) {
        if (periods[i] < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "THREADS: ERROR: period%d=%ld is negative\n", i + 1,
                            periods[i]);
            return -EINVAL;
        }
    }
    comp_id = hal_init("threads");
    if (comp_id < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "THREADS: ERROR: hal_init() failed\n");
        return comp_id;
    }
    for (int i = 0; i < 3; i++) {
        if (periods[i] == 0)
            continue;
        int rc = hal_create_thread(names[i], (unsigned long)periods[i], fps[i]);
        if (rc < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "THREADS: ERROR: could not create thread '%s'\n",
                            names[i]);
            delete_created(i);
            hal_exit(comp_id);
            /* LinuxCNC's threads returns -1 here ("Operation not
             * permitted (-1)" in rtapi_app's message). */
            (void)rc;
            return -1;
        }
    }
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    delete_created(3);
    hal_exit(comp_id);
}
