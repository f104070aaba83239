/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_cmds.c - halcmd's small commands: values (setp, getp, ptype,
 * sets, gets, stype), functions and threads (addf, delf, start, stop),
 * the lock, and setexact_for_test_suite_only.  Every command checks all its
 * arguments before changing anything; error texts follow LinuxCNC 2.9.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "halcmd.h"
#include "halcmd_parse.h"
#include "rtapi_proto.h"

/* ---- values ------------------------------------------------------------------- */

int do_setp_cmd(int argc, char **argv)
{
    (void)argc;
    char err[256];
    int rc = hal_q_setp(argv[1], argv[2], err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        if (rc == -EINVAL || rc == -ERANGE)
            halcmd_error("setp failed\n");
    } else {
        halcmd_info("Parameter '%s' set to %s\n", argv[1], argv[2]);
    }
    return rc;
}

int do_sets_cmd(int argc, char **argv)
{
    (void)argc;
    char err[256];
    int rc = hal_q_sets(argv[1], argv[2], err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        if (rc == -EINVAL || rc == -ERANGE)
            halcmd_error("sets failed\n");
    } else {
        halcmd_info("Signal '%s' set to %s\n", argv[1], argv[2]);
    }
    return rc;
}

int do_getp_cmd(int argc, char **argv)
{
    (void)argc;
    char buf[64], err[256];
    int rc = hal_q_getp(argv[1], buf, sizeof(buf), NULL, err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        return rc;
    }
    halcmd_output("%s\n", buf);
    return 0;
}

int do_gets_cmd(int argc, char **argv)
{
    (void)argc;
    char buf[64], err[256];
    int rc = hal_q_gets(argv[1], buf, sizeof(buf), NULL, err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        return rc;
    }
    halcmd_output("%s\n", buf);
    return 0;
}

int do_ptype_cmd(int argc, char **argv)
{
    (void)argc;
    hal_type_t t;
    char err[256];
    int rc = hal_q_getp(argv[1], NULL, 0, &t, err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        return rc;
    }
    halcmd_output("%s\n", hal_type_name(t));
    return 0;
}

int do_stype_cmd(int argc, char **argv)
{
    (void)argc;
    hal_type_t t;
    char err[256];
    int rc = hal_q_gets(argv[1], NULL, 0, &t, err, sizeof(err));
    if (rc) {
        halcmd_error("%s\n", err);
        return rc;
    }
    halcmd_output("%s\n", hal_type_name(t));
    return 0;
}

/* ---- threads --------------------------------------------------------------------- */

int do_addf_cmd(int argc, char **argv)
{
    int pos = -1;
    if (argc == 4) {
        char *end;
        long v = strtol(argv[3], &end, 0);
        if (*argv[3] == '\0' || *end != '\0' || v > 100000 || v < -100000) {
            halcmd_error("value '%s' invalid for position\n", argv[3]);
            return -EINVAL;
        }
        pos = (int)v;
    }
    int rc = hal_add_funct_to_thread(argv[1], argv[2], pos);
    if (rc)
        halcmd_error("addf failed\n");
    else
        halcmd_info("Function '%s' added to thread '%s'\n", argv[1], argv[2]);
    return rc;
}

int do_delf_cmd(int argc, char **argv)
{
    (void)argc;
    int rc = hal_del_funct_from_thread(argv[1], argv[2]);
    if (rc)
        halcmd_error("delf failed\n");
    else
        halcmd_info("Function '%s' removed from thread '%s'\n", argv[1], argv[2]);
    return rc;
}

int do_start_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    int rc = hal_start_threads();
    if (rc == 0)
        halcmd_info("Realtime threads started\n");
    return rc;
}

int do_stop_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    int rc = hal_stop_threads();
    if (rc == 0)
        halcmd_info("Realtime threads stopped\n");
    return rc;
}

/* ---- lock ----------------------------------------------------------------------- */

int do_lock_cmd(int argc, char **argv)
{
    unsigned char l = HAL_LOCK_ALL;
    if (argc > 1) {
        if (strcmp(argv[1], "all") == 0)
            l = HAL_LOCK_ALL;
        else if (strcmp(argv[1], "tune") == 0)
            l = HAL_LOCK_TUNE;
        else if (strcmp(argv[1], "none") == 0)
            l = HAL_LOCK_NONE;
        else {
            halcmd_error("Unknown lock type '%s'\n", argv[1]);
            return -EINVAL;
        }
    }
    return hal_set_lock(l);
}

int do_unlock_cmd(int argc, char **argv)
{
    unsigned char l = hal_get_lock();
    if (argc == 1 || strcmp(argv[1], "all") == 0)
        l = HAL_LOCK_NONE;
    else if (strcmp(argv[1], "tune") == 0)
        l &= (unsigned char)~HAL_LOCK_TUNE;
    else {
        halcmd_error("Unknown unlock type '%s'\n", argv[1]);
        return -EINVAL;
    }
    return hal_set_lock(l);
}

int do_setexact_cmd(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    if (halpr_set_exact() != 0) {
        halcmd_error("HAL_LIB: Cannot run 'setexact' after a thread has been created\n");
        return -EINVAL;
    }
    /* Periods are used exactly anyway in this implementation; the flag is
     * kept for compatibility (and reported like LinuxCNC). */
    halcmd_error("Warning: HAL_LIB: HAL will pretend that the exact base period requested "
                 "is possible.\nThis mode is not suitable for running real hardware.\n");
    return 0;
}
