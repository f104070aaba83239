/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halcmd_show.c - show, list, save and status, in LinuxCNC 2.9's formats
 * (scripts parse them, so every column width matters).
 *
 * These walk the lists directly under the HAL mutex; output goes to a
 * FILE (stdout, or the file of `save TYPE FILE`).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>

#include "halcmd.h"

static FILE *out;

static void o(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void o(const char *fmt, ...)
{
    if (hc.very_quiet)
        return;
    va_list ap;
    va_start(ap, fmt);
    vfprintf(out ? out : stdout, fmt, ap);
    va_end(ap);
}

static int match_any(int npat, char **pats, const char *name)
{
    if (npat == 0)
        return 1;
    for (int i = 0; i < npat; i++)
        if (hal_q_match(pats[i], name))
            return 1;
    return 0;
}

static const char *type5(int type)
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
static const char *value12(int type, const volatile void *p, char *buf, size_t len)
{
    switch (type) {
    case HAL_BIT: return *(const volatile hal_bit_t *)p ? "        TRUE" : "       FALSE";
    case HAL_FLOAT: snprintf(buf, len, "%12.7g", (double)*(const volatile hal_float_t *)p); break;
    case HAL_S32: snprintf(buf, len, "  %10ld", (long)*(const volatile hal_s32_t *)p); break;
    case HAL_U32:
        snprintf(buf, len, "  0x%08lX", (unsigned long)*(const volatile hal_u32_t *)p);
        break;
    case HAL_S64:
        snprintf(buf, len, "  %10" PRId64, (int64_t)*(const volatile hal_s64_t *)p);
        break;
    case HAL_U64:
        snprintf(buf, len, "  0x%016" PRIX64, (uint64_t)*(const volatile hal_u64_t *)p);
        break;
    default: return "   undef    ";
    }
    return buf;
}

/* Value column of pins and parameters (LinuxCNC's data_value2). */
static const char *value_pp(int type, const volatile void *p, char *buf, size_t len)
{
    switch (type) {
    case HAL_BIT: return *(const volatile hal_bit_t *)p ? "TRUE" : "FALSE";
    case HAL_FLOAT: snprintf(buf, len, "%.7g", (double)*(const volatile hal_float_t *)p); break;
    case HAL_S32: snprintf(buf, len, "%ld", (long)*(const volatile hal_s32_t *)p); break;
    case HAL_U32:
        snprintf(buf, len, "0x%08lX", (unsigned long)*(const volatile hal_u32_t *)p);
        break;
    case HAL_S64: snprintf(buf, len, "%" PRId64, (int64_t)*(const volatile hal_s64_t *)p); break;
    case HAL_U64:
        snprintf(buf, len, "0x%016" PRIX64, (uint64_t)*(const volatile hal_u64_t *)p);
        break;
    default: return "undef";
    }
    return buf;
}

static const char *pin_arrow(int dir)
{
    return dir == HAL_OUT ? "==>" : dir == HAL_IO ? "<=>" : "<==";
}

static const char *sig_arrow(int dir)
{
    return dir == HAL_OUT ? "<==" : dir == HAL_IO ? "<=>" : "==>";
}

/* ---- show ------------------------------------------------------------------ */

static void show_comps(int npat, char **pats)
{
    if (!hc.script) {
        o("Loaded HAL Components:\n");
        o("ID      Type  Name                                            PID   State\n");
    }
    for (hal_off_t off = hal_hdr->comp_list; off; off = ((hal_comp_t *)SHMPTR(off))->next) {
        hal_comp_t *c = SHMPTR(off);
        if (!match_any(npat, pats, c->name))
            continue;
        o(" %5d  %-4s  %-*s", c->id, c->type == HAL_COMP_RT ? "RT" : "User", HAL_NAME_LEN,
          c->name);
        if (c->type == HAL_COMP_RT)
            o(" %5s %s", "", c->ready ? "ready" : "initializing");
        else
            o(" %5d %s", c->pid, c->ready ? "ready" : "initializing");
        o("\n");
    }
    o("\n");
}

static void show_pins(int npat, char **pats)
{
    char buf[64];
    if (!hc.script) {
        o("Component Pins:\n");
        o("Owner   Type  Dir         Value  Name\n");
    }
    for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
        hal_pin_t *p = SHMPTR(off);
        if (!match_any(npat, pats, p->name))
            continue;
        hal_comp_t *c = SHMPTR(p->owner);
        const char *v = value_pp(p->type, halpr_pin_value(p), buf, sizeof(buf));
        if (hc.script)
            o("%s %s %s %s %s", c->name, type5(p->type), hal_pin_dir_name(p->dir), v, p->name);
        else
            o(" %5d  %5s %-3s  %12s  %s", c->id, type5(p->type), hal_pin_dir_name(p->dir), v,
              p->name);
        if (p->signal)
            o(" %s %s", pin_arrow(p->dir), ((hal_sig_t *)SHMPTR(p->signal))->name);
        o("\n");
    }
    o("\n");
}

static void show_params(int npat, char **pats)
{
    char buf[64];
    if (!hc.script) {
        o("Parameters:\n");
        o("Owner   Type  Dir         Value  Name\n");
    }
    for (hal_off_t off = hal_hdr->param_list; off; off = ((hal_param_t *)SHMPTR(off))->next) {
        hal_param_t *p = SHMPTR(off);
        if (!match_any(npat, pats, p->name))
            continue;
        hal_comp_t *c = SHMPTR(p->owner);
        const char *v = value_pp(p->type, halpr_param_value(p), buf, sizeof(buf));
        if (hc.script)
            o("%s %s %s %s %s\n", c->name, type5(p->type), hal_param_dir_name(p->dir), v,
              p->name);
        else
            o(" %5d  %5s %-3s  %12s  %s\n", c->id, type5(p->type), hal_param_dir_name(p->dir),
              v, p->name);
    }
    o("\n");
}

static void show_sigs(int npat, char **pats)
{
    char buf[64];
    if (!hc.script) {
        o("Signals:\n");
        o("Type          Value  Name     (linked to)\n");
    }
    for (hal_off_t off = hal_hdr->sig_list; off; off = ((hal_sig_t *)SHMPTR(off))->next) {
        hal_sig_t *s = SHMPTR(off);
        if (!match_any(npat, pats, s->name))
            continue;
        if (hc.script)
            o("%s  %s  %s", type5(s->type), value_pp(s->type, halpr_sig_value(s), buf, sizeof(buf)),
              s->name);
        else
            o("%s  %s  %s\n", type5(s->type),
              value12(s->type, halpr_sig_value(s), buf, sizeof(buf)), s->name);
        for (hal_off_t poff = hal_hdr->pin_list; poff; poff = ((hal_pin_t *)SHMPTR(poff))->next) {
            hal_pin_t *p = SHMPTR(poff);
            if (p->signal != off)
                continue;
            if (hc.script)
                o(" %s %s", sig_arrow(p->dir), p->name);
            else
                o("                         %s %s\n", sig_arrow(p->dir), p->name);
        }
        if (hc.script)
            o("\n");
    }
    o("\n");
}

static void show_functs(int npat, char **pats)
{
    if (!hc.script) {
        o("Exported Functions:\n");
        o("Owner   CodeAddr  Arg       FP   Users  Name\n");
    }
    for (hal_off_t off = hal_hdr->funct_list; off; off = ((hal_funct_t *)SHMPTR(off))->next) {
        hal_funct_t *f = SHMPTR(off);
        if (!match_any(npat, pats, f->name))
            continue;
        hal_comp_t *c = SHMPTR(f->owner);
        if (hc.script)
            o("%s %08" PRIx64 " %08" PRIx64 " %-3s %2d %s\n", c->name, f->funct, f->arg,
              f->uses_fp ? "YES" : "NO", f->users, f->name);
        else
            o(" %05d  %08" PRIx64 "  %08" PRIx64 "  %-3s  %5d   %s\n", c->id, f->funct, f->arg,
              f->uses_fp ? "YES" : "NO", f->users, f->name);
    }
    o("\n");
}

static void show_threads(int npat, char **pats)
{
    if (!hc.script) {
        o("Realtime Threads:\n");
        o("     Period  FP     Name               (     Time, Max-Time )\n");
    }
    for (hal_off_t off = hal_hdr->thread_list; off; off = ((hal_thread_t *)SHMPTR(off))->next) {
        hal_thread_t *t = SHMPTR(off);
        if (!match_any(npat, pats, t->name))
            continue;
        char pname[HAL_NAME_LEN + 8];
        snprintf(pname, sizeof(pname), "%s.time", t->name);
        hal_pin_t *tp = halpr_find_pin_by_name(pname);
        long runtime = tp ? (long)halpr_pin_value(tp)->s : 0;
        long maxtime = (long)*(hal_s32_t *)SHMPTR(t->maxtime);
        if (hc.script)
            o("%ld %-3s %s %8ld %ld", t->period, t->uses_fp ? "YES" : "NO", t->name, runtime,
              maxtime);
        else
            o("%11ld  %-3s  %20s ( %8ld, %8ld )\n", t->period, t->uses_fp ? "YES" : "NO",
              t->name, runtime, maxtime);
        int n = 1;
        for (hal_off_t e = t->funct_list; e; e = ((hal_funct_entry_t *)SHMPTR(e))->next) {
            hal_funct_t *f = SHMPTR(((hal_funct_entry_t *)SHMPTR(e))->funct);
            if (hc.script)
                o(" %s", f->name);
            else
                o("                 %2d %s\n", n++, f->name);
        }
        if (hc.script)
            o("\n");
    }
    o("\n");
}

static void show_aliases(int is_pin, int npat, char **pats)
{
    if (!hc.script) {
        o(is_pin ? "Pin Aliases:\n" : "Parameter Aliases:\n");
        o(" %-*s %s\n", HAL_NAME_LEN + 1, "Alias", "Original Name");
    }
    hal_off_t head = is_pin ? hal_hdr->pin_list : hal_hdr->param_list;
    for (hal_off_t off = head; off;) {
        const char *name;
        hal_off_t oldname;
        if (is_pin) {
            hal_pin_t *p = SHMPTR(off);
            name = p->name;
            oldname = p->oldname;
            off = p->next;
        } else {
            hal_param_t *p = SHMPTR(off);
            name = p->name;
            oldname = p->oldname;
            off = p->next;
        }
        if (oldname == 0 || !match_any(npat, pats, name))
            continue;
        if (hc.script)
            o("%s %s\n", name, ((hal_oldname_t *)SHMPTR(oldname))->name);
        else
            o(" %-*s %s\n", HAL_NAME_LEN + 1, name, ((hal_oldname_t *)SHMPTR(oldname))->name);
    }
    o("\n");
}

int do_show_cmd(int argc, char **argv)
{
    const char *type = argc > 1 ? argv[1] : "all";
    int npat = argc > 2 ? argc - 2 : 0;
    char **pats = argv + 2;
    out = stdout;
    if (strcmp(type, "all") == 0 || argc == 1) {
        hal_priv_lock();
        show_comps(npat, pats);
        show_pins(npat, pats);
        show_aliases(1, npat, pats);
        show_sigs(npat, pats);
        show_params(npat, pats);
        show_aliases(0, npat, pats);
        show_functs(npat, pats);
        show_threads(npat, pats);
        hal_priv_unlock();
        return 0;
    }
    void (*fn)(int, char **) = NULL;
    if (strcmp(type, "comp") == 0)
        fn = show_comps;
    else if (strcmp(type, "pin") == 0)
        fn = show_pins;
    else if (strcmp(type, "sig") == 0 || strcmp(type, "signal") == 0)
        fn = show_sigs;
    else if (strcmp(type, "param") == 0 || strcmp(type, "parameter") == 0)
        fn = show_params;
    else if (strcmp(type, "funct") == 0 || strcmp(type, "function") == 0)
        fn = show_functs;
    else if (strcmp(type, "thread") == 0)
        fn = show_threads;
    else if (strcmp(type, "alias") == 0) {
        hal_priv_lock();
        show_aliases(1, npat, pats);
        show_aliases(0, npat, pats);
        hal_priv_unlock();
        return 0;
    }
    if (fn == NULL) {
        halcmd_error("Unknown 'show' type '%s'\n", type);
        return -EINVAL;
    }
    hal_priv_lock();
    fn(npat, pats);
    hal_priv_unlock();
    return 0;
}

/* ---- list ------------------------------------------------------------------ */

int do_list_cmd(int argc, char **argv)
{
    const char *type = argv[1];
    char **pats = argv + 2;
    int npat = argc - 2;
    int want_type = HAL_TYPE_UNSPECIFIED;
    if (npat > 0 && strncmp(pats[0], "-t", 2) == 0) {
        want_type = hal_q_type_from_name(pats[0] + 2);
        if (want_type == HAL_TYPE_UNSPECIFIED) {
            halcmd_error("Unknown type '%s'\n", pats[0] + 2);
            return -EINVAL;
        }
        pats++;
        npat--;
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
    hal_priv_lock();
    for (hal_off_t off = *(&hal_hdr->comp_list + (int)kind); off; off = *(hal_off_t *)SHMPTR(off)) {
        const char *name;
        int t = HAL_TYPE_UNSPECIFIED;
        switch (kind) {
        case HAL_Q_COMP: name = ((hal_comp_t *)SHMPTR(off))->name; break;
        case HAL_Q_PIN:
            name = ((hal_pin_t *)SHMPTR(off))->name;
            t = ((hal_pin_t *)SHMPTR(off))->type;
            break;
        case HAL_Q_PARAM:
            name = ((hal_param_t *)SHMPTR(off))->name;
            t = ((hal_param_t *)SHMPTR(off))->type;
            break;
        case HAL_Q_SIG:
            name = ((hal_sig_t *)SHMPTR(off))->name;
            t = ((hal_sig_t *)SHMPTR(off))->type;
            break;
        case HAL_Q_FUNCT: name = ((hal_funct_t *)SHMPTR(off))->name; break;
        default: name = ((hal_thread_t *)SHMPTR(off))->name; break;
        }
        if (want_type != HAL_TYPE_UNSPECIFIED && t != HAL_TYPE_UNSPECIFIED && t != want_type)
            continue;
        if (!match_any(npat, pats, name))
            continue;
        o("%s ", name);
    }
    hal_priv_unlock();
    o("\n");
    return 0;
}

/* ---- save ------------------------------------------------------------------ */

static void save_comps(void)
{
    o("# components\n");
    /* oldest first */
    int n = 0;
    for (hal_off_t off = hal_hdr->comp_list; off; off = ((hal_comp_t *)SHMPTR(off))->next)
        n++;
    hal_off_t *v = calloc((size_t)n + 1, sizeof(*v));
    if (v == NULL)
        return;
    int i = 0;
    for (hal_off_t off = hal_hdr->comp_list; off; off = ((hal_comp_t *)SHMPTR(off))->next)
        v[i++] = off;
    for (i = n - 1; i >= 0; i--) {
        hal_comp_t *c = SHMPTR(v[i]);
        if (c->type != HAL_COMP_RT)
            continue;
        if (c->loaded_by_loadrt)
            o("loadrt %s %s\n", c->name, c->insmod_args ? (char *)SHMPTR(c->insmod_args) : "");
        else
            o("#loadrt %s  (not loaded by loadrt, no args saved)\n", c->name);
    }
    free(v);
}

static void save_aliases(void)
{
    o("# pin aliases\n");
    for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
        hal_pin_t *p = SHMPTR(off);
        if (p->oldname)
            o("alias pin %s %s\n", ((hal_oldname_t *)SHMPTR(p->oldname))->name, p->name);
    }
    o("# param aliases\n");
    for (hal_off_t off = hal_hdr->param_list; off; off = ((hal_param_t *)SHMPTR(off))->next) {
        hal_param_t *p = SHMPTR(off);
        if (p->oldname)
            o("alias param %s %s\n", ((hal_oldname_t *)SHMPTR(p->oldname))->name, p->name);
    }
}

static int sig_has_pins(hal_off_t soff)
{
    for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next)
        if (((hal_pin_t *)SHMPTR(off))->signal == soff)
            return 1;
    return 0;
}

static void save_sigs(int only_unlinked)
{
    o("# signals\n");
    for (hal_off_t off = hal_hdr->sig_list; off; off = ((hal_sig_t *)SHMPTR(off))->next) {
        hal_sig_t *s = SHMPTR(off);
        if (only_unlinked && sig_has_pins(off))
            continue;
        o("newsig %s %s\n", s->name, type5(s->type));
    }
}

static void save_links(int arrows)
{
    o("# links\n");
    for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
        hal_pin_t *p = SHMPTR(off);
        if (!p->signal)
            continue;
        o("linkps %s %s %s\n", p->name, arrows ? pin_arrow(p->dir) : "",
          ((hal_sig_t *)SHMPTR(p->signal))->name);
    }
}

/* save net / neta: every signal as newsig, then one linksp per pin (neta:
 * with the arrow seen from the signal). */
static void save_nets(int arrows)
{
    o("# nets\n");
    for (hal_off_t soff = hal_hdr->sig_list; soff; soff = ((hal_sig_t *)SHMPTR(soff))->next) {
        hal_sig_t *s = SHMPTR(soff);
        o("newsig %s %s\n", s->name, type5(s->type));
        for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
            hal_pin_t *p = SHMPTR(off);
            if (p->signal == soff)
                o("linksp %s %s %s\n", s->name, arrows ? sig_arrow(p->dir) : "", p->name);
        }
    }
}

/* save netl / netla (and the nets of save all): linked signals only, one
 * net line each: writer, I/O pins, then readers, with "=>" before the
 * readers when arrows are asked for and there is a writer. */
static void save_nets_linked(int arrows)
{
    o("# nets\n");
    for (hal_off_t soff = hal_hdr->sig_list; soff; soff = ((hal_sig_t *)SHMPTR(soff))->next) {
        hal_sig_t *s = SHMPTR(soff);
        if (!sig_has_pins(soff))
            continue;
        o("net %s", s->name);
        for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
            hal_pin_t *p = SHMPTR(off);
            if (p->signal == soff && p->dir == HAL_OUT)
                o(" %s", p->name);
        }
        for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
            hal_pin_t *p = SHMPTR(off);
            if (p->signal == soff && p->dir == HAL_IO)
                o(" %s", p->name);
        }
        int first = 1;
        for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
            hal_pin_t *p = SHMPTR(off);
            if (p->signal == soff && p->dir == HAL_IN) {
                if (first && arrows && s->writers)
                    o(" =>");
                first = 0;
                o(" %s", p->name);
            }
        }
        o("\n");
    }
}

static void save_params(void)
{
    char buf[64];
    o("# parameter values\n");
    for (hal_off_t off = hal_hdr->param_list; off; off = ((hal_param_t *)SHMPTR(off))->next) {
        hal_param_t *p = SHMPTR(off);
        if (p->dir == HAL_RO)
            continue;
        o("setp %s %s\n", p->name, value12(p->type, halpr_param_value(p), buf, sizeof(buf)));
    }
}

static void save_unconnected_inpins(void)
{
    char buf[64];
    o("# unconnected pin values\n");
    for (hal_off_t off = hal_hdr->pin_list; off; off = ((hal_pin_t *)SHMPTR(off))->next) {
        hal_pin_t *p = SHMPTR(off);
        if (p->signal || p->dir == HAL_OUT)
            continue;
        o("setp %s %s\n", p->name, value12(p->type, halpr_pin_value(p), buf, sizeof(buf)));
    }
}

static void save_threads(void)
{
    o("# realtime thread/function links\n");
    for (hal_off_t off = hal_hdr->thread_list; off; off = ((hal_thread_t *)SHMPTR(off))->next) {
        hal_thread_t *t = SHMPTR(off);
        for (hal_off_t e = t->funct_list; e; e = ((hal_funct_entry_t *)SHMPTR(e))->next) {
            hal_funct_t *f = SHMPTR(((hal_funct_entry_t *)SHMPTR(e))->funct);
            o("addf %s %s\n", f->name, t->name);
        }
    }
}

int do_save_cmd(int argc, char **argv)
{
    const char *type = argc > 1 ? argv[1] : "all";
    out = stdout;
    FILE *f = NULL;
    if (argc > 2) {
        f = fopen(argv[2], "w");
        if (f == NULL) {
            halcmd_error("Can't open 'save' destination '%s'\n", argv[2]);
            return -errno;
        }
        out = f;
    }
    int rc = 0;
    hal_priv_lock();
    if (strcmp(type, "all") == 0 || strcmp(type, "allu") == 0) {
        int u = strcmp(type, "allu") == 0;
        save_comps();
        save_aliases();
        save_sigs(1);
        save_nets_linked(1);
        save_params();
        if (u)
            save_unconnected_inpins();
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
        save_params();
    } else if (strcmp(type, "unconnectedinpins") == 0) {
        save_unconnected_inpins();
    } else if (strcmp(type, "thread") == 0) {
        save_threads();
    } else {
        rc = -EINVAL;
    }
    hal_priv_unlock();
    if (f != NULL)
        fclose(f);
    out = stdout;
    if (rc)
        halcmd_error("Unknown 'save' type '%s'\n", type);
    return rc;
}

/* ---- status ------------------------------------------------------------------ */

static void status_lock(void)
{
    unsigned char l = hal_hdr->lock;
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

static void status_mem(void)
{
    o("HAL memory status\n");
    o("  used/total shared memory:   %ld/%ld\n",
      (long)(hal_hdr->size - (hal_hdr->top - hal_hdr->bot)), (long)hal_hdr->size);
    o("  active/recycled components: %d/%d\n", hal_hdr->active_comps, hal_hdr->recycled_comps);
    o("  active/recycled pins:       %d/%d\n", hal_hdr->active_pins, hal_hdr->recycled_pins);
    o("  active/recycled parameters: %d/%d\n", hal_hdr->active_params, hal_hdr->recycled_params);
    o("  active/recycled aliases:    %d/%d\n", hal_hdr->active_aliases, hal_hdr->recycled_aliases);
    o("  active/recycled signals:    %d/%d\n", hal_hdr->active_sigs, hal_hdr->recycled_sigs);
    o("  active/recycled functions:  %d/%d\n", hal_hdr->active_functs, hal_hdr->recycled_functs);
    o("  active/recycled threads:    %d/%d\n", hal_hdr->active_threads, hal_hdr->recycled_threads);
}

int do_status_cmd(int argc, char **argv)
{
    const char *type = argc > 1 ? argv[1] : "all";
    out = stdout;
    hal_priv_lock();
    int rc = 0;
    if (strcmp(type, "all") == 0) {
        status_lock();
        status_mem();
    } else if (strcmp(type, "lock") == 0) {
        status_lock();
    } else if (strcmp(type, "mem") == 0) {
        status_mem();
    } else {
        rc = -EINVAL;
    }
    hal_priv_unlock();
    if (rc)
        halcmd_error("Unknown 'status' type '%s'\n", type);
    return rc;
}
