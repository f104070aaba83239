/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * vparport - create, drive and watch virtual parallel ports (docs/vparport.md).
 *
 *   vparport create NAME [--ecr] [--control-pp] [--spp] [--replace]
 *   vparport remove NAME
 *   vparport drive NAME PIN=0|1|z ...
 *   vparport get NAME [PIN ...]
 *   vparport show NAME
 *   vparport log NAME [--pin PIN]... [--from N] [--clear]
 *   vparport counters NAME [--reset]
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "vpp.h"

static const char usage[] =
    "usage: vparport create NAME [--ecr] [--control-pp] [--spp] [--replace]\n"
    "       vparport remove NAME\n"
    "       vparport drive NAME PIN=0|1|z ...\n"
    "       vparport get NAME [PIN ...]\n"
    "       vparport show NAME\n"
    "       vparport log NAME [--pin PIN]... [--from N] [--clear]\n"
    "       vparport counters NAME [--reset]\n"
    "NAME without '/' is /dev/shm/vparport.NAME; PIN is a DB-25 signal pin 1..17.\n";

static const char *const reg_names[VPP_NREGS] = {"data", "status", "control", "ecr", "other"};

static int fail(const char *msg)
{
    fprintf(stderr, "vparport: %s\n", msg);
    return 1;
}

static int parse_pin(const char *s, int *pin)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (!*s || *end || v < 1 || v > 17)
        return -1;
    *pin = (int)v;
    return 0;
}

static int cmd_create(int argc, char **argv)
{
    unsigned opts = 0;
    int replace = 0;
    char err[600];
    for (int i = 3; i < argc; i++) {
        if (!strcmp(argv[i], "--ecr"))
            opts |= VPP_OPT_ECR;
        else if (!strcmp(argv[i], "--control-pp"))
            opts |= VPP_OPT_CONTROL_PP;
        else if (!strcmp(argv[i], "--spp"))
            opts |= VPP_OPT_NO_BIDIR;
        else if (!strcmp(argv[i], "--replace"))
            replace = 1;
        else {
            fprintf(stderr, "vparport: create: unknown option '%s'\n%s", argv[i], usage);
            return 2;
        }
    }
    if (vpp_create(argv[2], opts, replace, err, sizeof(err)))
        return fail(err);
    return 0;
}

/* "PIN=LEVEL" -> pin, level (-1 = z).  Checked all before any is applied. */
static int parse_drive(const char *arg, int *pin, int *level)
{
    char buf[32];
    const char *eq = strchr(arg, '=');
    if (!eq || (size_t)(eq - arg) >= sizeof(buf))
        return -1;
    memcpy(buf, arg, (size_t)(eq - arg));
    buf[eq - arg] = '\0';
    if (parse_pin(buf, pin))
        return -1;
    if (!strcmp(eq + 1, "0"))
        *level = 0;
    else if (!strcmp(eq + 1, "1"))
        *level = 1;
    else if (!strcmp(eq + 1, "z") || !strcmp(eq + 1, "Z"))
        *level = -1;
    else
        return -1;
    return 0;
}

static int cmd_drive(struct vpp_state *st, int argc, char **argv)
{
    int pin[64], level[64], n = argc - 3;
    if (n < 1 || n > 64) {
        fputs(usage, stderr);
        return 2;
    }
    for (int i = 0; i < n; i++)
        if (parse_drive(argv[3 + i], &pin[i], &level[i])) {
            fprintf(stderr, "vparport: drive: bad 'PIN=LEVEL' '%s' (PIN 1..17, LEVEL 0, 1 or z)\n",
                    argv[3 + i]);
            return 2;
        }
    for (int i = 0; i < n; i++)
        vpp_drive(st, pin[i], level[i]);
    return 0;
}

static int cmd_get(struct vpp_state *st, int argc, char **argv)
{
    uint32_t pins = vpp_pins(st);
    int want[17], n = 0;
    for (int i = 3; i < argc; i++) {
        if (n == 17 || parse_pin(argv[i], &want[n])) {
            fprintf(stderr, "vparport: get: bad pin '%s' (1..17)\n", argv[i]);
            return 2;
        }
        n++;
    }
    if (n == 0)
        for (; n < 17; n++)
            want[n] = n + 1;
    for (int i = 0; i < n; i++)
        printf("%s%d=%u", i ? " " : "", want[i], (pins >> want[i]) & 1u);
    printf("\n");
    return 0;
}

static void print_pin_row(const char *label, uint32_t mask, uint32_t val)
{
    printf("%-8s", label);
    for (int p = 1; p <= 17; p++) {
        if (!(mask & VPP_PIN(p)))
            printf("  .");
        else
            printf("  %u", (val >> p) & 1u);
    }
    printf("\n");
}

static int cmd_show(struct vpp_state *st)
{
    uint32_t o = st->options;
    printf("options  %s, control pins %s%s\n", (o & VPP_OPT_ECR) ? "ECR" : "no ECR",
           (o & VPP_OPT_CONTROL_PP) ? "push-pull" : "open collector",
           (o & VPP_OPT_NO_BIDIR) ? ", SPP only (no data direction)" : "");
    printf("owner    %d\n", (int)st->owner_pid);
    printf("data     0x%02x\ncontrol  0x%02x\n", st->data_latch, st->control_latch);
    if (o & VPP_OPT_ECR)
        printf("ecr      0x%02x\n", (st->ecr & 0xfcu) | 1u);
    printf("pin     ");
    for (int p = 1; p <= 17; p++)
        printf(" %2d", p);
    printf("\n");
    uint32_t lv, drive = vpp_port_drive(st, &lv);
    print_pin_row("port", drive, lv);
    print_pin_row("outside", st->ext_drive, st->ext_level);
    print_pin_row("level", VPP_ALL_PINS, vpp_pins(st));
    printf("log      %llu entries\n", (unsigned long long)vpp_log_head(st));
    return 0;
}

static int cmd_counters(struct vpp_state *st, int argc, char **argv)
{
    if (argc > 3 && !strcmp(argv[3], "--reset")) {
        vpp_counters_reset(st);
        return 0;
    }
    if (argc > 3) {
        fputs(usage, stderr);
        return 2;
    }
    for (int i = 0; i < VPP_NREGS; i++)
        printf("%s reads %llu writes %llu\n", reg_names[i], (unsigned long long)st->reads[i],
               (unsigned long long)st->writes[i]);
    printf("contention %llu\n", (unsigned long long)st->contention);
    return 0;
}

/* One line per log entry where a selected pin changed: "T_NS PIN=L ...". */
static int cmd_log(struct vpp_state *st, int argc, char **argv)
{
    uint32_t sel = 0;
    uint64_t from = 0;
    for (int i = 3; i < argc; i++) {
        int pin;
        if (!strcmp(argv[i], "--pin") && i + 1 < argc && !parse_pin(argv[i + 1], &pin)) {
            sel |= VPP_PIN(pin);
            i++;
        } else if (!strcmp(argv[i], "--from") && i + 1 < argc) {
            from = strtoull(argv[++i], NULL, 10);
        } else if (!strcmp(argv[i], "--clear")) {
            vpp_log_clear(st);
            return 0;
        } else {
            fprintf(stderr, "vparport: log: bad argument '%s'\n%s", argv[i], usage);
            return 2;
        }
    }
    if (!sel)
        sel = VPP_ALL_PINS;
    struct vpp_log_entry *buf = malloc(VPP_LOG_LEN * sizeof(*buf));
    if (!buf)
        return fail("out of memory");
    uint64_t first;
    size_t n = vpp_log_read(st, from, buf, VPP_LOG_LEN, &first);
    uint32_t prev = 0;
    for (size_t i = 0; i < n; i++) {
        if (i > 0 && !((buf[i].pins ^ prev) & sel))
            continue;
        prev = buf[i].pins;
        printf("%llu", (unsigned long long)buf[i].t_ns);
        for (int p = 1; p <= 17; p++)
            if (sel & VPP_PIN(p))
                printf(" %d=%u", p, (buf[i].pins >> p) & 1u);
        printf("\n");
    }
    free(buf);
    return 0;
}

int main(int argc, char **argv)
{
    char err[600];
    if (argc < 3) {
        if (argc == 2 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
            fputs(usage, stdout);
            return 0;
        }
        fputs(usage, stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "create"))
        return cmd_create(argc, argv);
    if (!strcmp(cmd, "remove")) {
        if (argc != 3) {
            fputs(usage, stderr);
            return 2;
        }
        return vpp_remove(argv[2], err, sizeof(err)) ? fail(err) : 0;
    }
    static const char *const known[] = {"drive", "get", "show", "log", "counters"};
    int k = -1;
    for (int i = 0; i < 5; i++)
        if (!strcmp(cmd, known[i]))
            k = i;
    if (k < 0) {
        fprintf(stderr, "vparport: unknown command '%s'\n%s", cmd, usage);
        return 2;
    }
    struct vpp_state *st;
    if (vpp_open(argv[2], &st, err, sizeof(err)))
        return fail(err);
    int r;
    switch (k) {
    case 0:
        r = cmd_drive(st, argc, argv);
        break;
    case 1:
        r = cmd_get(st, argc, argv);
        break;
    case 2:
        r = argc == 3 ? cmd_show(st) : (fputs(usage, stderr), 2);
        break;
    case 3:
        r = cmd_log(st, argc, argv);
        break;
    default:
        r = cmd_counters(st, argc, argv);
        break;
    }
    vpp_close(st);
    return r;
}
