/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_show.h - what show/list (halcmd_show.c) and save/status
 * (halcmd_save.c) share: output, LinuxCNC's value columns and arrows, and
 * snapshots of HAL objects (hal_query.h) as arrays.
 */
#ifndef HM_HALCMD_SHOW_H
#define HM_HALCMD_SHOW_H

#include <stddef.h>
#include <stdio.h>

#include "hal_query.h"

/* Output goes to stdout, or to the file of `save TYPE FILE`. */
void halcmd_set_out(FILE *f);
void o(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
int match_any(int npat, char **pats, const char *name);
const char *type5(int type);
const char *value12(int type, const hal_data_u *v, char *buf, size_t len);
const char *pin_arrow(int dir);
const char *sig_arrow(int dir);

/* Every object of a kind, in show order: hal_q_comp_t, hal_q_pin_t (pins
 * and parameters), hal_q_sig_t, hal_q_funct_t or hal_q_thread_t records. */
typedef struct {
    void *v;
    size_t n, cap;
} qlist_t;
int qlist_get(qlist_t *l, hal_q_kind_t kind);
void qlist_free(qlist_t *l);

/* Indexes of the linked pins, grouped by signal (pin order inside a
 * group); pins_of_signal finds a signal's first one. */
size_t *pins_by_signal(const qlist_t *pins, size_t *n);
size_t pins_of_signal(const qlist_t *pins, const size_t *idx, size_t n, const char *sig);
/* Function names of a thread in execution order (malloc'd, *n set). */
char (*thread_functs(const char *thread, int *n))[HAL_NAME_LEN + 1];

#endif /* HM_HALCMD_SHOW_H */
