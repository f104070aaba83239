/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_show.c - show and list, in LinuxCNC 2.9's formats (scripts parse
 * them, so every column width matters).  HAL is read through snapshots of
 * hal_query.h; the value formatting is shared with save (halcmd_save.c).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "halcmd.h"
#include "halcmd_show.h"

static FILE *out;

void halcmd_set_out(FILE *f) { out = f; }

void o(const char *fmt, ...)
{
    if (hc.very_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    vfprintf(out ? out : halcmd_stdout(), fmt, ap);
    va_end(ap);
}

int match_any(int npat, char **pats, const char *name)
{
    if (npat == 0)
        return 1;
    for (int i = 0; i < npat; i++)
        if (hal_q_match(pats[i], name))
            return 1;
    return 0;
}

const char *type5(int type)
{
    switch (type) {
    case HAL_BIT: return "bit  ";
    case HAL_FLOAT: return "float";
    case HAL_S32: return "s32  ";
    case HAL_U32: return "u32  ";
    case HAL_S64: return "s64  ";
    case HAL_U64: return "u64  ";
    default: return "undef";
    }
}

/* Value column of signals and `save` (LinuxCNC's data_value). */
const char *value12(int type, const hal_data_u *v, char *buf, size_t len)
{
    switch (type) {
    case HAL_BIT: return v->b ? "        TRUE" : "       FALSE";
    case HAL_FLOAT: snprintf(buf, len, "%12.7g", (double)v->f); break;
    case HAL_S32: snprintf(buf, len, "  %10ld", (long)v->s); break;
    case HAL_U32: snprintf(buf, len, "  0x%08lX", (unsigned long)v->u); break;
    case HAL_S64: snprintf(buf, len, "  %10" PRId64, (int64_t)v->ls); break;
    case HAL_U64: snprintf(buf, len, "  0x%016" PRIX64, (uint64_t)v->lu); break;
    default: return "   undef    ";
    }
    return buf;
}

/* Value column of pins and parameters (LinuxCNC's data_value2). */
static const char *value_pp(int type, const hal_data_u *v, char *buf, size_t len)
{
    switch (type) {
    case HAL_BIT: return v->b ? "TRUE" : "FALSE";
    case HAL_FLOAT: snprintf(buf, len, "%.7g", (double)v->f); break;
    case HAL_S32: snprintf(buf, len, "%ld", (long)v->s); break;
    case HAL_U32: snprintf(buf, len, "0x%08lX", (unsigned long)v->u); break;
    case HAL_S64: snprintf(buf, len, "%" PRId64, (int64_t)v->ls); break;
    case HAL_U64: snprintf(buf, len, "0x%016" PRIX64, (uint64_t)v->lu); break;
    default: return "undef";
    }
    return buf;
}

const char *pin_arrow(int dir)
{
    return dir == HAL_OUT ? "==>" : dir == HAL_IO ? "<=>" : "<==";
}

const char *sig_arrow(int dir)
{
    return dir == HAL_OUT ? "<==" : dir == HAL_IO ? "<=>" : "==>";
}

/* ---- snapshots into arrays ------------------------------------------------- */

#define COLLECT(fn, qtype)                                         \
    static int fn##_cb(const qtype *x, void *ctx)                  \
    {                                                              \
        qlist_t *l = ctx;                                          \
        if (l->n == l->cap) {                                      \
            size_t cap = l->cap ? l->cap * 2 : 64;                 \
            void *v = realloc(l->v, cap * sizeof(qtype));          \
            if (v == NULL)                                         \
                return 1;                                          \
            l->v = v;                                              \
            l->cap = cap;                                          \
        }                                                          \
        ((qtype *)l->v)[l->n++] = *x;                              \
        return 0;                                                  \
    }
COLLECT(comps, hal_q_comp_t)
COLLECT(pins, hal_q_pin_t)
COLLECT(sigs, hal_q_sig_t)
COLLECT(functs, hal_q_funct_t)
COLLECT(threads, hal_q_thread_t)

int qlist_get(qlist_t *l, hal_q_kind_t kind)
{
    memset(l, 0, sizeof(*l));
    switch (kind) {
    case HAL_Q_COMP: return hal_q_each_comp(comps_cb, l);
    case HAL_Q_PIN: return hal_q_each_pin(pins_cb, l);
    case HAL_Q_PARAM: return hal_q_each_param(pins_cb, l);
    case HAL_Q_SIG: return hal_q_each_sig(sigs_cb, l);
    case HAL_Q_FUNCT: return hal_q_each_funct(functs_cb, l);
    case HAL_Q_THREAD: return hal_q_each_thread(threads_cb, l);
    default: return -EINVAL;
    }
}

void qlist_free(qlist_t *l)
{
    free(l->v);
    memset(l, 0, sizeof(*l));
}

/* ---- show ------------------------------------------------------------------ */

static void show_comps(int npat, char **pats)
{
    if (!hc.script) {
        o("Loaded HAL Components:\n");
        o("ID      Type  Name                                            PID   State\n");
    }
    qlist_t l;
    qlist_get(&l, HAL_Q_COMP);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_comp_t *c = (const hal_q_comp_t *)l.v + i;
        if (!match_any(npat, pats, c->name))
            continue;
        o(" %5d  %-4s  %-*s", c->id, c->realtime ? "RT" : "User", HAL_NAME_LEN, c->name);
        if (c->realtime)
            o(" %5s %s", "", c->ready ? "ready" : "initializing");
        else
            o(" %5d %s", c->pid, c->ready ? "ready" : "initializing");
        o("\n");
    }
    qlist_free(&l);
    o("\n");
}

static void show_pins_params(int is_pin, int npat, char **pats)
{
    char buf[64];
    if (!hc.script) {
        o(is_pin ? "Component Pins:\n" : "Parameters:\n");
        o("Owner   Type  Dir         Value  Name\n");
    }
    qlist_t l;
    qlist_get(&l, is_pin ? HAL_Q_PIN : HAL_Q_PARAM);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_pin_t *p = (const hal_q_pin_t *)l.v + i;
        if (!match_any(npat, pats, p->name))
            continue;
        const char *dir = is_pin ? hal_pin_dir_name(p->dir) : hal_param_dir_name(p->dir);
        const char *v = value_pp(p->type, &p->value, buf, sizeof(buf));
        if (hc.script)
            o("%s %s %s %s %s", p->owner, type5(p->type), dir, v, p->name);
        else
            o(" %5d  %5s %-3s  %12s  %s", p->owner_id, type5(p->type), dir, v, p->name);
        if (is_pin && p->signal[0])
            o(" %s %s", pin_arrow(p->dir), p->signal);
        o("\n");
    }
    qlist_free(&l);
    o("\n");
}

static void show_pins(int npat, char **pats) { show_pins_params(1, npat, pats); }
static void show_params(int npat, char **pats) { show_pins_params(0, npat, pats); }

/* Pins grouped by signal, each group in pin (name) order: a signal's
 * pins are found by binary search instead of a walk over all pins. */
static const hal_q_pin_t *by_sig_base;

static int by_sig_cmp(const void *a, const void *b)
{
    const hal_q_pin_t *pa = by_sig_base + *(const size_t *)a;
    const hal_q_pin_t *pb = by_sig_base + *(const size_t *)b;
    int c = strcmp(pa->signal, pb->signal);
    return c != 0 ? c : (pa < pb ? -1 : pa > pb);
}

size_t *pins_by_signal(const qlist_t *pins, size_t *n)
{
    size_t *idx = malloc((pins->n ? pins->n : 1) * sizeof(*idx));
    *n = 0;
    if (idx == NULL)
        return NULL;
    const hal_q_pin_t *p = pins->v;
    for (size_t i = 0; i < pins->n; i++)
        if (p[i].signal[0] != '\0')
            idx[(*n)++] = i;
    by_sig_base = p;
    qsort(idx, *n, sizeof(*idx), by_sig_cmp);
    return idx;
}

/* First position in idx (sorted by pins_by_signal) of a pin of `sig`. */
size_t pins_of_signal(const qlist_t *pins, const size_t *idx, size_t n, const char *sig)
{
    const hal_q_pin_t *p = pins->v;
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (strcmp(p[idx[mid]].signal, sig) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

static void show_sigs(int npat, char **pats)
{
    char buf[64];
    if (!hc.script) {
        o("Signals:\n");
        o("Type          Value  Name     (linked to)\n");
    }
    qlist_t sigs, pins;
    qlist_get(&sigs, HAL_Q_SIG);
    qlist_get(&pins, HAL_Q_PIN);
    size_t nlinked;
    size_t *idx = pins_by_signal(&pins, &nlinked);
    const hal_q_pin_t *pv = pins.v;
    for (size_t i = 0; i < sigs.n; i++) {
        const hal_q_sig_t *s = (const hal_q_sig_t *)sigs.v + i;
        if (!match_any(npat, pats, s->name))
            continue;
        if (hc.script)
            o("%s  %s  %s", type5(s->type), value_pp(s->type, &s->value, buf, sizeof(buf)),
              s->name);
        else
            o("%s  %s  %s\n", type5(s->type), value12(s->type, &s->value, buf, sizeof(buf)),
              s->name);
        for (size_t k = idx ? pins_of_signal(&pins, idx, nlinked, s->name) : nlinked;
             k < nlinked && strcmp(pv[idx[k]].signal, s->name) == 0; k++) {
            const hal_q_pin_t *p = &pv[idx[k]];
            if (hc.script)
                o(" %s %s", sig_arrow(p->dir), p->name);
            else
                o("                         %s %s\n", sig_arrow(p->dir), p->name);
        }
        if (hc.script)
            o("\n");
    }
    free(idx);
    qlist_free(&sigs);
    qlist_free(&pins);
    o("\n");
}

static void show_functs(int npat, char **pats)
{
    if (!hc.script) {
        o("Exported Functions:\n");
        o("Owner   CodeAddr  Arg       FP   Users  Name\n");
    }
    qlist_t l;
    qlist_get(&l, HAL_Q_FUNCT);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_funct_t *f = (const hal_q_funct_t *)l.v + i;
        if (!match_any(npat, pats, f->name))
            continue;
        if (hc.script)
            o("%s %08llx %08llx %-3s %2d %s\n", f->owner, f->code_addr, f->arg,
              f->uses_fp ? "YES" : "NO", f->users, f->name);
        else
            o(" %05d  %08llx  %08llx  %-3s  %5d   %s\n", f->owner_id, f->code_addr, f->arg,
              f->uses_fp ? "YES" : "NO", f->users, f->name);
    }
    qlist_free(&l);
    o("\n");
}

/* Function names of a thread (malloc'd; *n set), in execution order. */
char (*thread_functs(const char *thread, int *n))[HAL_NAME_LEN + 1]
{
    int cnt = hal_q_thread_functs(thread, NULL, 0);
    *n = 0;
    if (cnt <= 0)
        return NULL;
    char(*names)[HAL_NAME_LEN + 1] = calloc((size_t)cnt, sizeof(*names));
    if (names == NULL)
        return NULL;
    int got = hal_q_thread_functs(thread, names, cnt);
    *n = got < cnt ? got : cnt;
    return names;
}

static void show_threads(int npat, char **pats)
{
    if (!hc.script) {
        o("Realtime Threads:\n");
        o("     Period  FP     Name               (     Time, Max-Time )\n");
    }
    qlist_t l;
    qlist_get(&l, HAL_Q_THREAD);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_thread_t *t = (const hal_q_thread_t *)l.v + i;
        if (!match_any(npat, pats, t->name))
            continue;
        if (hc.script)
            o("%ld %-3s %s %8ld %ld", t->period, t->uses_fp ? "YES" : "NO", t->name, t->runtime,
              t->maxtime);
        else
            o("%11ld  %-3s  %20s ( %8ld, %8ld )\n", t->period, t->uses_fp ? "YES" : "NO",
              t->name, t->runtime, t->maxtime);
        int n;
        char(*names)[HAL_NAME_LEN + 1] = thread_functs(t->name, &n);
        for (int k = 0; k < n; k++) {
            if (hc.script)
                o(" %s", names[k]);
            else
                o("                 %2d %s\n", k + 1, names[k]);
        }
        free(names);
        if (hc.script)
            o("\n");
    }
    qlist_free(&l);
    o("\n");
}

static void show_aliases(int is_pin, int npat, char **pats)
{
    if (!hc.script) {
        o(is_pin ? "Pin Aliases:\n" : "Parameter Aliases:\n");
        o(" %-*s %s\n", HAL_NAME_LEN + 1, "Alias", "Original Name");
    }
    qlist_t l;
    qlist_get(&l, is_pin ? HAL_Q_PIN : HAL_Q_PARAM);
    for (size_t i = 0; i < l.n; i++) {
        const hal_q_pin_t *p = (const hal_q_pin_t *)l.v + i;
        if (p->original[0] == '\0' || !match_any(npat, pats, p->name))
            continue;
        if (hc.script)
            o("%s %s\n", p->name, p->original);
        else
            o(" %-*s %s\n", HAL_NAME_LEN + 1, p->name, p->original);
    }
    qlist_free(&l);
    o("\n");
}

int do_show_cmd(int argc, char **argv)
{
    const char *type = argc > 1 ? argv[1] : "all";
    int npat = argc > 2 ? argc - 2 : 0;
    char **pats = argv + 2;
    out = halcmd_stdout();
    if (strcmp(type, "all") == 0 || argc == 1) {
        show_comps(npat, pats);
        show_pins(npat, pats);
        show_aliases(1, npat, pats);
        show_sigs(npat, pats);
        show_params(npat, pats);
        show_aliases(0, npat, pats);
        show_functs(npat, pats);
        show_threads(npat, pats);
        return 0;
    }
    if (strcmp(type, "alias") == 0) {
        show_aliases(1, npat, pats);
        show_aliases(0, npat, pats);
        return 0;
    }
    static const struct {
        const char *name, *alt;
        void (*fn)(int, char **);
    } kinds[] = {
        {"comp", "comp", show_comps},         {"pin", "pin", show_pins},
        {"sig", "signal", show_sigs},         {"param", "parameter", show_params},
        {"funct", "function", show_functs},   {"thread", "thread", show_threads},
    };
    for (size_t i = 0; i < sizeof(kinds) / sizeof(kinds[0]); i++) {
        if (strcmp(type, kinds[i].name) == 0 || strcmp(type, kinds[i].alt) == 0) {
            kinds[i].fn(npat, pats);
            return 0;
        }
    }
    halcmd_error("Unknown 'show' type '%s'\n", type);
    return -EINVAL;
}

/* ---- list ------------------------------------------------------------------ */

typedef struct {
    int npat;
    char **pats;
    hal_type_t want;
} list_ctx_t;

static void list_one(const list_ctx_t *lc, const char *name, hal_type_t t)
{
    if (lc->want != HAL_TYPE_UNSPECIFIED && t != HAL_TYPE_UNSPECIFIED && t != lc->want)
        return;
    if (match_any(lc->npat, lc->pats, name))
        o("%s ", name);
}

int do_list_cmd(int argc, char **argv)
{
    const char *type = argv[1];
    list_ctx_t lc = {argc - 2, argv + 2, HAL_TYPE_UNSPECIFIED};
    if (lc.npat > 0 && strncmp(lc.pats[0], "-t", 2) == 0) {
        lc.want = hal_q_type_from_name(lc.pats[0] + 2);
        if (lc.want == HAL_TYPE_UNSPECIFIED) {
            halcmd_error("Unknown type '%s'\n", lc.pats[0] + 2);
            return -EINVAL;
        }
        lc.pats++;
        lc.npat--;
    }
    hal_q_kind_t kind;
    if (strcmp(type, "comp") == 0)
        kind = HAL_Q_COMP;
    else if (strcmp(type, "pin") == 0)
        kind = HAL_Q_PIN;
    else if (strcmp(type, "sig") == 0 || strcmp(type, "signal") == 0)
        kind = HAL_Q_SIG;
    else if (strcmp(type, "param") == 0 || strcmp(type, "parameter") == 0)
        kind = HAL_Q_PARAM;
    else if (strcmp(type, "funct") == 0 || strcmp(type, "function") == 0)
        kind = HAL_Q_FUNCT;
    else if (strcmp(type, "thread") == 0)
        kind = HAL_Q_THREAD;
    else {
        halcmd_error("Unknown 'list' type '%s'\n", type);
        return -EINVAL;
    }
    out = halcmd_stdout();
    qlist_t l;
    qlist_get(&l, kind);
    for (size_t i = 0; i < l.n; i++) {
        switch (kind) {
        case HAL_Q_COMP:
            list_one(&lc, ((const hal_q_comp_t *)l.v)[i].name, HAL_TYPE_UNSPECIFIED);
            break;
        case HAL_Q_PIN:
        case HAL_Q_PARAM: {
            const hal_q_pin_t *p = (const hal_q_pin_t *)l.v + i;
            list_one(&lc, p->name, p->type);
            break;
        }
        case HAL_Q_SIG: {
            const hal_q_sig_t *s = (const hal_q_sig_t *)l.v + i;
            list_one(&lc, s->name, s->type);
            break;
        }
        case HAL_Q_FUNCT:
            list_one(&lc, ((const hal_q_funct_t *)l.v)[i].name, HAL_TYPE_UNSPECIFIED);
            break;
        default:
            list_one(&lc, ((const hal_q_thread_t *)l.v)[i].name, HAL_TYPE_UNSPECIFIED);
            break;
        }
    }
    qlist_free(&l);
    o("\n");
    return 0;
}
