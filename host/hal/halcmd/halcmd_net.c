/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_net.c - signals and links: net (checked whole before anything
 * changes), newsig, delsig, linkps/linksp/linkpp, unlinkp, alias, unalias.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "halcmd.h"
#include "halcmd_parse.h"
#include "rtapi_proto.h"

static int is_arrow(const char *s)
{
    return strcmp(s, "=>") == 0 || strcmp(s, "<=") == 0 || strcmp(s, "<=>") == 0 ||
           strcmp(s, "==>") == 0 || strcmp(s, "<==") == 0;
}

/* ---- net and links ----------------------------------------------------------- */

int do_newsig_cmd(int argc, char **argv)
{
    (void)argc;
    hal_type_t t = hal_q_type_from_name(argv[2]);
    if (t == HAL_TYPE_UNSPECIFIED) {
        halcmd_error("Unknown signal type '%s'\n", argv[2]);
        halcmd_error("newsig failed\n");
        return -EINVAL;
    }
    if (hal_q_pin(argv[1], NULL) == 0) {
        halcmd_error("Signal name '%s' must not be the same as a pin.\n", argv[1]);
        return -EINVAL;
    }
    int rc = hal_signal_new(argv[1], t);
    if (rc)
        halcmd_error("newsig failed\n");
    return rc;
}

static int first_sig(const char *name, void *ctx)
{
    snprintf(ctx, HAL_NAME_LEN + 1, "%s", name);
    return 1; /* stop after the first */
}

int do_delsig_cmd(int argc, char **argv)
{
    (void)argc;
    if (strcmp(argv[1], "all") != 0)
        return hal_signal_delete(argv[1]);
    for (;;) {
        char name[HAL_NAME_LEN + 1] = "";
        hal_q_foreach(HAL_Q_SIG, NULL, first_sig, name);
        if (name[0] == '\0')
            return 0;
        int rc = hal_signal_delete(name);
        if (rc)
            return rc;
    }
}

/* What `net` finds before it changes anything: the signal (if it exists)
 * and the writers it has or will have, with the names LinuxCNC's messages
 * use. */
typedef struct {
    const char *sig;
    int exists;
    hal_type_t type;
    int writers, bidirs;
    char writer[HAL_NAME_LEN + 1], bidir[HAL_NAME_LEN + 1];
} net_plan_t;

static int net_plan_init(net_plan_t *np, const char *sig)
{
    memset(np, 0, sizeof(*np));
    np->sig = sig;
    np->type = HAL_TYPE_UNSPECIFIED;
    hal_q_sig_t s;
    if (hal_q_sig(sig, &s) != 0)
        return 0;
    np->exists = 1;
    np->type = s.type;
    np->writers = s.writers;
    np->bidirs = s.bidirs;
    int n = hal_q_sig_pins(sig, NULL, 0);
    char(*names)[HAL_NAME_LEN + 1] = n > 0 ? calloc((size_t)n, sizeof(*names)) : NULL;
    if (n > 0 && names == NULL)
        return -ENOMEM;
    n = hal_q_sig_pins(sig, names, n);
    for (int i = 0; i < n; i++) {
        hal_q_pin_t p;
        if (hal_q_pin(names[i], &p) != 0)
            continue;
        if (p.dir == HAL_OUT)
            snprintf(np->writer, sizeof(np->writer), "%s", p.name);
        if (p.dir == HAL_IO && np->bidir[0] == '\0')
            snprintf(np->bidir, sizeof(np->bidir), "%s", p.name);
    }
    free(names);
    return 0;
}

/* Messages are LinuxCNC's, also where LinuxCNC would have made half a net
 * (for a new signal it prints libhal's line, then "link failed"). */
static int net_refuse(const net_plan_t *np, const char *halmsg, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int net_refuse(const net_plan_t *np, const char *halmsg, const char *fmt, ...)
{
    if (np->exists) {
        char buf[512];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(buf, sizeof(buf), fmt, ap);
        va_end(ap);
        halcmd_error("%s\n", buf);
    } else {
        rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: %s\n", halmsg);
        halcmd_error("link failed\n");
    }
    return -EINVAL;
}

/* Check one pin against the plan and add it; 1 when it is to be skipped
 * (already on this signal), 0 when it is to be linked, -errno to fail. */
static int net_check_pin(net_plan_t *np, const char *name, const hal_q_pin_t *p)
{
    char msg[256];
    if (p->signal[0] != '\0' && strcmp(p->signal, np->sig) != 0) {
        halcmd_error("Pin '%s' was already linked to signal '%s'\n", name, p->signal);
        return -EINVAL;
    }
    if (p->signal[0] != '\0')
        return 1;
    if (np->type == HAL_TYPE_UNSPECIFIED)
        np->type = p->type;
    if (p->type != np->type) {
        snprintf(msg, sizeof(msg), "type mismatch '%s' <- '%s'", name, np->sig);
        return net_refuse(np, msg, "Signal '%s' of type '%s' cannot add pin '%s' of type '%s'",
                          np->sig, hal_type_name(np->type), name, hal_type_name(p->type));
    }
    if (p->dir == HAL_OUT && (np->writers > 0 || np->bidirs > 0)) {
        snprintf(msg, sizeof(msg), "signal '%s' already has output or I/O pin(s)", np->sig);
        return net_refuse(np, msg, "Signal '%s' can not add OUT pin '%s', it already has %s pin '%s'",
                          np->sig, name, np->writers > 0 ? "OUT" : "I/O",
                          np->writers > 0 ? np->writer : np->bidir);
    }
    if (p->dir == HAL_IO && np->writers > 0) {
        snprintf(msg, sizeof(msg), "signal '%s' already has output pin", np->sig);
        return net_refuse(np, msg, "Signal '%s' can not add I/O pin '%s', it already has OUT pin '%s'",
                          np->sig, name, np->writer);
    }
    if (p->dir == HAL_OUT) {
        np->writers++;
        snprintf(np->writer, sizeof(np->writer), "%s", p->name);
    } else if (p->dir == HAL_IO) {
        np->bidirs++;
        if (np->bidir[0] == '\0')
            snprintf(np->bidir, sizeof(np->bidir), "%s", p->name);
    }
    return 0;
}

/* Link the pins (all checked); on a failure only a concurrent change can
 * cause, undo what was done. */
static int net_apply(const net_plan_t *np, const char **pins, const int *skip, int npins)
{
    int rc;
    if (!np->exists) {
        rc = hal_signal_new(np->sig, np->type);
        if (rc)
            return rc;
    }
    for (int i = 0; i < npins; i++) {
        if (skip[i])
            continue;
        rc = hal_link(pins[i], np->sig);
        if (rc) {
            for (int j = 0; j < i; j++)
                if (!skip[j])
                    hal_unlink(pins[j]);
            if (!np->exists)
                hal_signal_delete(np->sig);
            halcmd_error("link failed\n");
            return rc;
        }
        halcmd_info("Pin '%s' linked to signal '%s'\n", pins[i], np->sig);
    }
    return 0;
}

int do_net_cmd(int argc, char **argv)
{
    const char *sig = argv[1];
    const char *pins[HALCMD_MAX_TOKENS];
    int skip[HALCMD_MAX_TOKENS];
    char(*seen)[HAL_NAME_LEN + 1] = calloc(HALCMD_MAX_TOKENS, sizeof(*seen));
    if (seen == NULL)
        return -ENOMEM;
    int npins = 0, rc = 0;
    for (int i = 2; i < argc; i++)
        if (!is_arrow(argv[i]))
            pins[npins++] = argv[i];
    net_plan_t np;
    if (hal_q_pin(sig, NULL) == 0) {
        halcmd_error("Signal name '%s' must not be the same as a pin.  "
                     "Did you omit the signal name?\n",
                     sig);
        rc = -EINVAL;
    } else if ((rc = net_plan_init(&np, sig)) != 0) {
        /* out of memory */
    } else if (hal_get_lock() & HAL_LOCK_CONFIG) {
        if (!np.exists) {
            rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: signal_new called while HAL is locked\n");
        } else {
            rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: link called while HAL locked\n");
            halcmd_error("link failed\n");
        }
        rc = -EPERM;
    }
    /* The whole command is checked before anything changes. */
    for (int i = 0; i < npins && rc == 0; i++) {
        hal_q_pin_t p;
        if (hal_q_pin(pins[i], &p) != 0) {
            halcmd_error("Pin '%s' does not exist\n", pins[i]);
            rc = -ENOENT;
            break;
        }
        skip[i] = 0;
        for (int j = 0; j < i; j++) /* the same pin twice is linked once */
            if (strcmp(seen[j], p.name) == 0)
                skip[i] = 1;
        snprintf(seen[i], HAL_NAME_LEN + 1, "%s", p.name);
        if (!skip[i]) {
            int r = net_check_pin(&np, pins[i], &p);
            if (r < 0)
                rc = r;
            skip[i] = r > 0;
        }
    }
    free(seen);
    if (rc == 0 && !np.exists && npins == 0) {
        halcmd_error("net requires at least one pin to create signal '%s'\n", sig);
        rc = -EINVAL;
    }
    return rc != 0 ? rc : net_apply(&np, pins, skip, npins);
}

static int link_ps(const char *pin, const char *sig)
{
    int rc = hal_link(pin, sig);
    if (rc)
        halcmd_error("link failed\n");
    return rc;
}

/* LinuxCNC 2.9 takes exactly two words (no arrow) for linkps/linksp. */
int do_linkps_cmd(int argc, char **argv)
{
    (void)argc;
    return link_ps(argv[1], argv[2]);
}

int do_linksp_cmd(int argc, char **argv)
{
    (void)argc;
    return link_ps(argv[2], argv[1]);
}

/* linkpp P1 P2: a signal named like P1 linking both pins (deprecated in
 * LinuxCNC 2.9, which warns).  All checks first; nothing is made on error. */
int do_linkpp_cmd(int argc, char **argv)
{
    (void)argc;
    const char *p1 = argv[1], *p2 = argv[2];
    halcmd_error("Warning: linkpp command is deprecated, use 'net'\n");
    hal_q_pin_t a, b;
    if (hal_q_pin(p1, &a) != 0 || hal_q_pin(p2, &b) != 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: pin '%s' not found\n",
                        hal_q_pin(p1, NULL) != 0 ? p1 : p2);
        halcmd_error("link failed\n");
        return -ENOENT;
    }
    if (a.type != b.type) {
        rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: type mismatch '%s' <- '%s'\n", p2, p1);
        halcmd_error("link failed\n");
        return -EINVAL;
    }
    if (a.signal[0] || b.signal[0]) {
        const hal_q_pin_t *l = a.signal[0] ? &a : &b;
        rtapi_print_msg(RTAPI_MSG_ERR, "HAL: ERROR: pin '%s' is linked to '%s', cannot link to '%s'\n",
                        l->name, l->signal, p1);
        halcmd_error("link failed\n");
        return -EINVAL;
    }
    int w1 = a.dir == HAL_OUT, w2 = b.dir == HAL_OUT;
    if ((w1 && (w2 || b.dir == HAL_IO)) || (w2 && a.dir == HAL_IO)) {
        rtapi_print_msg(RTAPI_MSG_ERR,
                        "HAL: ERROR: signal '%s' already has output or I/O pin(s)\n", p1);
        halcmd_error("link failed\n");
        return -EINVAL;
    }
    int rc = hal_signal_new(p1, a.type);
    if (rc == 0 && (rc = hal_link(p1, p1)) == 0 && (rc = hal_link(p2, p1)) != 0) {
        hal_unlink(p1);
    }
    if (rc != 0) {
        if (hal_q_sig(p1, NULL) == 0 && hal_q_sig_pins(p1, NULL, 0) == 0)
            hal_signal_delete(p1);
        halcmd_error("link failed\n");
    }
    return rc;
}

int do_unlinkp_cmd(int argc, char **argv)
{
    (void)argc;
    int rc = hal_unlink(argv[1]);
    if (rc)
        halcmd_error("unlink failed\n");
    return rc;
}

/* ---- aliases -------------------------------------------------------------------- */

int do_alias_cmd(int argc, char **argv)
{
    (void)argc;
    int rc;
    if (strcmp(argv[1], "pin") == 0)
        rc = hal_pin_alias(argv[2], argv[3]);
    else if (strcmp(argv[1], "param") == 0)
        rc = hal_param_alias(argv[2], argv[3]);
    else {
        halcmd_error("Unknown alias type '%s'\n", argv[1]);
        return -EINVAL;
    }
    if (rc)
        halcmd_error("alias failed\n");
    return rc;
}

int do_unalias_cmd(int argc, char **argv)
{
    (void)argc;
    int rc;
    if (strcmp(argv[1], "pin") == 0)
        rc = hal_pin_alias(argv[2], NULL);
    else if (strcmp(argv[1], "param") == 0)
        rc = hal_param_alias(argv[2], NULL);
    else {
        halcmd_error("Unknown unalias type '%s'\n", argv[1]);
        return -EINVAL;
    }
    if (rc)
        halcmd_error("unalias failed\n");
    return rc;
}

