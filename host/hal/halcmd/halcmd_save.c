/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_save.c - save (HAL as halcmd commands) and status (lock and
 * memory), in LinuxCNC 2.9's formats, read through hal_query.h.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "halcmd.h"
#include "halcmd_show.h"

/* ---- save ------------------------------------------------------------------ */

static void save_comps(void)
{
    o("# components\n");
    qlist_t l;
    qlist_get(&l, HAL_Q_COMP);
    /* oldest first */
    for (size_t i = l.n; i-- > 0;) {
        const hal_q_comp_t *c = (const hal_q_comp_t *)l.v + i;
        if (!c->realtime)
            continue;
        if (c->loaded_by_loadrt)
            o("loadrt %s %s\n", c->name, c->insmod_args);
        else
            o("#loadrt %s  (not loaded by loadrt, no args saved)\n", c->name);
    }
    qlist_free(&l);
}

static void save_aliases(void)
{
    for (int is_pin = 1; is_pin >= 0; is_pin--) {
        o(is_pin ? "# pin aliases\n" : "# param aliases\n");
        qlist_t l;
        qlist_get(&l, is_pin ? HAL_Q_PIN : HAL_Q_PARAM);
        for (size_t i = 0; i < l.n; i++) {
            const hal_q_pin_t *p = (const hal_q_pin_t *)l.v + i;
            if (p->original[0])
                o("alias %s %s %s\n", is_pin ? "pin" : "param", p->original, p->name);
        }
        qlist_free(&l);
    }
}

/* The pins (snapshot) and their grouping by signal. */
typedef struct {
    qlist_t pins;
    size_t *idx, nlinked;
} linked_t;

static void linked_get(linked_t *lk)
{
    qlist_get(&lk->pins, HAL_Q_PIN);
    lk->idx = pins_by_signal(&lk->pins, &lk->nlinked);
}

static void linked_free(linked_t *lk)
{
    free(lk->idx);
    qlist_free(&lk->pins);
}

/* Call fn for each pin of sig, in pin order. */
static void each_pin_of(const linked_t *lk, const char *sig,
                        void (*fn)(const hal_q_pin_t *p, void *ctx), void *ctx)
{
    if (lk->idx == NULL)
        return;
    const hal_q_pin_t *pv = lk->pins.v;
    for (size_t k = pins_of_signal(&lk->pins, lk->idx, lk->nlinked, sig);
         k < lk->nlinked && strcmp(pv[lk->idx[k]].signal, sig) == 0; k++)
        fn(&pv[lk->idx[k]], ctx);
}

static void count_pin(const hal_q_pin_t *p, void *ctx)
{
    (void)p;
    (*(int *)ctx)++;
}

static int sig_has_pins(const linked_t *lk, const char *sig)
{
    int n = 0;
    each_pin_of(lk, sig, count_pin, &n);
    return n > 0;
}

static void save_sigs(int only_unlinked)
{
    o("# signals\n");
    linked_t lk;
    linked_get(&lk);
    qlist_t l;
    qlist_get(&l, HAL_Q_SIG);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_sig_t *s = (const hal_q_sig_t *)l.v + i;
        if (only_unlinked && sig_has_pins(&lk, s->name))
            continue;
        o("newsig %s %s\n", s->name, type5(s->type));
    }
    qlist_free(&l);
    linked_free(&lk);
}

static void save_links(int arrows)
{
    o("# links\n");
    qlist_t l;
    qlist_get(&l, HAL_Q_PIN);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_pin_t *p = (const hal_q_pin_t *)l.v + i;
        if (p->signal[0])
            o("linkps %s %s %s\n", p->name, arrows ? pin_arrow(p->dir) : "", p->signal);
    }
    qlist_free(&l);
}

typedef struct {
    const char *sig;
    int arrows, dir, first, writers;
} net_line_t;

static void linksp_line(const hal_q_pin_t *p, void *ctx)
{
    const net_line_t *nl = ctx;
    o("linksp %s %s %s\n", nl->sig, nl->arrows ? sig_arrow(p->dir) : "", p->name);
}

/* save net / neta: every signal as newsig, then one linksp per pin (neta:
 * with the arrow seen from the signal). */
static void save_nets(int arrows)
{
    o("# nets\n");
    linked_t lk;
    linked_get(&lk);
    qlist_t l;
    qlist_get(&l, HAL_Q_SIG);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_sig_t *s = (const hal_q_sig_t *)l.v + i;
        o("newsig %s %s\n", s->name, type5(s->type));
        net_line_t nl = {s->name, arrows, 0, 0, 0};
        each_pin_of(&lk, s->name, linksp_line, &nl);
    }
    qlist_free(&l);
    linked_free(&lk);
}

static void net_pin(const hal_q_pin_t *p, void *ctx)
{
    net_line_t *nl = ctx;
    if (p->dir != nl->dir)
        return;
    if (nl->dir == HAL_IN && nl->first && nl->arrows && nl->writers)
        o(" =>");
    nl->first = 0;
    o(" %s", p->name);
}

/* save netl / netla (and the nets of save all): linked signals only, one
 * net line each: writer, I/O pins, then readers, with "=>" before the
 * readers when arrows are asked for and there is a writer. */
static void save_nets_linked(int arrows)
{
    o("# nets\n");
    linked_t lk;
    linked_get(&lk);
    qlist_t l;
    qlist_get(&l, HAL_Q_SIG);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_sig_t *s = (const hal_q_sig_t *)l.v + i;
        if (!sig_has_pins(&lk, s->name))
            continue;
        o("net %s", s->name);
        static const int order[] = {HAL_OUT, HAL_IO, HAL_IN};
        for (int k = 0; k < 3; k++) {
            net_line_t nl = {s->name, arrows, order[k], 1, s->writers};
            each_pin_of(&lk, s->name, net_pin, &nl);
        }
        o("\n");
    }
    qlist_free(&l);
    linked_free(&lk);
}

static void save_values(int pins)
{
    char buf[64];
    o(pins ? "# unconnected pin values\n" : "# parameter values\n");
    qlist_t l;
    qlist_get(&l, pins ? HAL_Q_PIN : HAL_Q_PARAM);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_pin_t *p = (const hal_q_pin_t *)l.v + i;
        if (pins ? (p->signal[0] || p->dir == HAL_OUT) : p->dir == HAL_RO)
            continue;
        o("setp %s %s\n", p->name, value12(p->type, &p->value, buf, sizeof(buf)));
    }
    qlist_free(&l);
}

static void save_threads(void)
{
    o("# realtime thread/function links\n");
    qlist_t l;
    qlist_get(&l, HAL_Q_THREAD);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_thread_t *t = (const hal_q_thread_t *)l.v + i;
        int n;
        char(*names)[HAL_NAME_LEN + 1] = thread_functs(t->name, &n);
        for (int k = 0; k < n; k++)
            o("addf %s %s\n", names[k], t->name);
        free(names);
    }
    qlist_free(&l);
}

static int save_type(const char *type)
{
    if (strcmp(type, "all") == 0 || strcmp(type, "allu") == 0) {
        save_comps();
        save_aliases();
        save_sigs(1);
        save_nets_linked(1);
        save_values(0);
        if (strcmp(type, "allu") == 0)
            save_values(1);
        save_threads();
    } else if (strcmp(type, "comp") == 0) {
        save_comps();
    } else if (strcmp(type, "alias") == 0) {
        save_aliases();
    } else if (strcmp(type, "sig") == 0 || strcmp(type, "signal") == 0) {
        save_sigs(0);
    } else if (strcmp(type, "sigu") == 0) {
        save_sigs(1);
    } else if (strcmp(type, "link") == 0 || strcmp(type, "linka") == 0) {
        save_links(type[4] == 'a');
    } else if (strcmp(type, "net") == 0 || strcmp(type, "neta") == 0) {
        save_nets(type[3] == 'a');
    } else if (strcmp(type, "netl") == 0) {
        save_nets_linked(0);
    } else if (strcmp(type, "netla") == 0 || strcmp(type, "netal") == 0) {
        save_nets_linked(1);
    } else if (strcmp(type, "param") == 0 || strcmp(type, "parameter") == 0) {
        save_values(0);
    } else if (strcmp(type, "unconnectedinpins") == 0) {
        save_values(1);
    } else if (strcmp(type, "thread") == 0) {
        save_threads();
    } else {
        return -EINVAL;
    }
    return 0;
}

int do_save_cmd(int argc, char **argv)
{
    const char *type = argc > 1 ? argv[1] : "all";
    FILE *f = NULL;
    if (argc > 2) {
        f = fopen(argv[2], "w");
        if (f == NULL) {
            halcmd_error("Can't open 'save' destination '%s'\n", argv[2]);
            return -errno;
        }
    }
    halcmd_set_out(f != NULL ? f : halcmd_stdout());
    int rc = save_type(type);
    if (f != NULL)
        fclose(f);
    halcmd_set_out(halcmd_stdout());
    if (rc)
        halcmd_error("Unknown 'save' type '%s'\n", type);
    return rc;
}

/* ---- status ------------------------------------------------------------------ */

static void status_lock(const hal_q_status_t *st)
{
    unsigned char l = st->lock;
    o("HAL locking status:\n");
    o("  current lock value %d (%02x)\n", l, l);
    if (l == HAL_LOCK_NONE)
        o("  HAL_LOCK_NONE - nothing is locked\n");
    if (l & HAL_LOCK_LOAD)
        o("  HAL_LOCK_LOAD    - loading of new components is locked\n");
    if (l & HAL_LOCK_CONFIG)
        o("  HAL_LOCK_CONFIG  - link and addf is locked\n");
    if (l & HAL_LOCK_PARAMS)
        o("  HAL_LOCK_PARAMS  - setting params is locked\n");
    if (l & HAL_LOCK_RUN)
        o("  HAL_LOCK_RUN     - running/stopping HAL is locked\n");
}

static void status_mem(const hal_q_status_t *st)
{
    o("HAL memory status\n");
    o("  used/total shared memory:   %ld/%ld\n", st->shmem_used, st->shmem_total);
    o("  active/recycled components: %d/%d\n", st->active_comps, st->recycled_comps);
    o("  active/recycled pins:       %d/%d\n", st->active_pins, st->recycled_pins);
    o("  active/recycled parameters: %d/%d\n", st->active_params, st->recycled_params);
    o("  active/recycled aliases:    %d/%d\n", st->active_aliases, st->recycled_aliases);
    o("  active/recycled signals:    %d/%d\n", st->active_sigs, st->recycled_sigs);
    o("  active/recycled functions:  %d/%d\n", st->active_functs, st->recycled_functs);
    o("  active/recycled threads:    %d/%d\n", st->active_threads, st->recycled_threads);
}

int do_status_cmd(int argc, char **argv)
{
    const char *type = argc > 1 ? argv[1] : "all";
    halcmd_set_out(halcmd_stdout());
    hal_q_status_t st;
    if (hal_q_status(&st) != 0)
        return -EINVAL;
    if (strcmp(type, "all") == 0) {
        status_lock(&st);
        status_mem(&st);
    } else if (strcmp(type, "lock") == 0) {
        status_lock(&st);
    } else if (strcmp(type, "mem") == 0) {
        status_mem(&st);
    } else {
        halcmd_error("Unknown 'status' type '%s'\n", type);
        return -EINVAL;
    }
    return 0;
}
