/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of the virtual parallel port model (sim/parport): registers
 * against pin levels as a PC port has them (inverted status bit 7 and
 * control bits 0, 1, 3; direction bit; ECR modes; open-collector vs
 * push-pull control pins), the log, the claim and the shared file.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../check.h"
#include "vpp.h"

static char dir[64];

static struct vpp_state *make(const char *name, unsigned opts, char *path, size_t len)
{
    char err[600];
    struct vpp_state *st = NULL;
    snprintf(path, len, "%s/%s", dir, name);
    CHECK_EQ_INT(vpp_create(path, opts, 1, err, sizeof(err)), 0);
    CHECK_EQ_INT(vpp_open(path, &st, err, sizeof(err)), 0);
    return st;
}

static int pin(struct vpp_state *st, int n)
{
    return (int)((vpp_pins(st) >> n) & 1u);
}

static void test_power_on(void)
{
    char path[128];
    struct vpp_state *st = make("pon", 0, path, sizeof(path));
    /* control 0x0c: nInit (16) high, nSelectIn (17) asserted = low */
    CHECK_EQ_INT(vpp_inb(st, 2, 0), 0xc0 | 0x0c);
    CHECK_EQ_INT(pin(st, 1), 1);
    CHECK_EQ_INT(pin(st, 14), 1);
    CHECK_EQ_INT(pin(st, 16), 1);
    CHECK_EQ_INT(pin(st, 17), 0);
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0x00);
    /* nothing attached: status inputs high; Busy (11) high reads as bit 7 = 0 */
    CHECK_EQ_INT(vpp_inb(st, 1, 0), 0x7e);
    CHECK_EQ_INT(vpp_log_head(st), 0);
    vpp_close(st);
}

static void test_status_bits(void)
{
    char path[128];
    struct vpp_state *st = make("status", 0, path, sizeof(path));
    static const struct {
        int pin;
        uint8_t bit;
        int inverted;
    } map[] = {{10, 0x40, 0}, {11, 0x80, 1}, {12, 0x20, 0}, {13, 0x10, 0}, {15, 0x08, 0}};
    for (size_t i = 0; i < 5; i++) {
        vpp_drive(st, map[i].pin, 0);
        uint8_t s = vpp_inb(st, 1, 0);
        CHECK_EQ_INT(!!(s & map[i].bit), map[i].inverted ? 1 : 0);
        vpp_drive(st, map[i].pin, 1);
        s = vpp_inb(st, 1, 0);
        CHECK_EQ_INT(!!(s & map[i].bit), map[i].inverted ? 0 : 1);
        vpp_drive(st, map[i].pin, -1);
    }
    CHECK_EQ_INT(vpp_inb(st, 1, 0) & 0x07, 0x06); /* reserved 1s, no timeout */
    CHECK_EQ_INT(vpp_drive(st, 0, 1), -EINVAL);
    CHECK_EQ_INT(vpp_drive(st, 18, 1), -EINVAL);
    vpp_close(st);
}

static void test_control_inversions_and_oc(void)
{
    char path[128];
    struct vpp_state *st = make("ctl", 0, path, sizeof(path));
    vpp_outb(st, 2, 0x0f, 10);
    CHECK_EQ_INT(pin(st, 1), 0);
    CHECK_EQ_INT(pin(st, 14), 0);
    CHECK_EQ_INT(pin(st, 16), 1);
    CHECK_EQ_INT(pin(st, 17), 0);
    vpp_outb(st, 2, 0x00, 20);
    CHECK_EQ_INT(pin(st, 1), 1);
    CHECK_EQ_INT(pin(st, 14), 1);
    CHECK_EQ_INT(pin(st, 16), 0);
    CHECK_EQ_INT(pin(st, 17), 1);
    /* open collector: released pins can be pulled low from outside */
    vpp_outb(st, 2, 0x04, 30); /* all released (high) */
    CHECK_EQ_INT(vpp_inb(st, 2, 30), 0xc4);
    vpp_drive(st, 1, 0);
    vpp_drive(st, 16, 0);
    CHECK_EQ_INT(vpp_inb(st, 2, 30), 0xc1); /* bit 0 set = pin 1 low; bit 2 clear */
    CHECK_EQ_INT(st->contention, 0);
    /* the port pulling low against an outside high driver is contention */
    vpp_drive(st, 1, 1);
    vpp_outb(st, 2, 0x05, 40);
    CHECK_EQ_INT(pin(st, 1), 0);
    CHECK(st->contention > 0);
    /* bits 4 and 5 read back as written, 6 and 7 read 1 */
    vpp_outb(st, 2, 0xf4, 50);
    CHECK_EQ_INT(vpp_inb(st, 2, 50) & 0xf0, 0xf0);
    vpp_close(st);
}

static void test_control_push_pull(void)
{
    char path[128];
    struct vpp_state *st = make("pp", VPP_OPT_CONTROL_PP, path, sizeof(path));
    vpp_outb(st, 2, 0x04, 0);
    vpp_drive(st, 14, 0);
    CHECK_EQ_INT(pin(st, 14), 1); /* the port wins */
    CHECK_EQ_INT(vpp_inb(st, 2, 0) & 0x02, 0);
    CHECK(st->contention > 0);
    vpp_close(st);
}

static void test_data_direction(void)
{
    char path[128];
    struct vpp_state *st = make("dir", 0, path, sizeof(path));
    vpp_outb(st, 0, 0xa5, 0);
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0xa5);
    CHECK_EQ_INT(pin(st, 2), 1);
    CHECK_EQ_INT(pin(st, 3), 0);
    vpp_outb(st, 2, 0x20, 0); /* drivers off: pins float high */
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0xff);
    vpp_drive(st, 2, 0);
    vpp_drive(st, 9, 0);
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0x7e);
    CHECK_EQ_INT(st->data_latch, 0xa5); /* latch kept */
    vpp_outb(st, 2, 0x00, 0);           /* drivers back on, against the outside */
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0xa5);
    CHECK(st->contention > 0);
    vpp_close(st);

    /* an SPP-only port ignores the direction bit */
    st = make("spp", VPP_OPT_NO_BIDIR, path, sizeof(path));
    vpp_outb(st, 0, 0x55, 0);
    vpp_outb(st, 2, 0x20, 0);
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0x55);
    vpp_close(st);
}

static void test_ecr(void)
{
    char path[128];
    struct vpp_state *st = make("noecr", 0, path, sizeof(path));
    CHECK_EQ_INT(vpp_inb(st, VPP_ECR_OFFSET, 0), 0xff);
    vpp_outb(st, VPP_ECR_OFFSET, 0x34, 0);
    CHECK_EQ_INT(vpp_inb(st, VPP_ECR_OFFSET, 0), 0xff);
    CHECK_EQ_INT(st->writes[VPP_REG_ECR], 1);
    vpp_close(st);

    st = make("ecr", VPP_OPT_ECR, path, sizeof(path));
    CHECK_EQ_INT(vpp_inb(st, VPP_ECR_OFFSET, 0), 0x15);
    /* SPP mode (000): the direction bit does nothing */
    vpp_outb(st, 0, 0x12, 0);
    vpp_outb(st, 2, 0x20, 0);
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0x12);
    /* PS/2 mode (001): it works */
    vpp_outb(st, VPP_ECR_OFFSET, 0x34, 0);
    CHECK_EQ_INT(vpp_inb(st, VPP_ECR_OFFSET, 0), 0x35);
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0xff);
    /* EPP mode (100) too */
    vpp_outb(st, VPP_ECR_OFFSET, 0x94, 0);
    CHECK_EQ_INT(vpp_inb(st, VPP_ECR_OFFSET, 0), 0x95);
    CHECK_EQ_INT(vpp_inb(st, 0, 0), 0xff);
    /* nothing else is decoded */
    CHECK_EQ_INT(vpp_inb(st, 3, 0), 0xff);
    CHECK_EQ_INT(vpp_inb(st, 4, 0), 0xff);
    CHECK_EQ_INT(st->reads[VPP_REG_OTHER], 2);
    vpp_close(st);
}

static void test_log(void)
{
    char path[128];
    struct vpp_log_entry e[8];
    uint64_t first;
    struct vpp_state *st = make("log", 0, path, sizeof(path));
    vpp_outb(st, 0, 0x01, 100);
    vpp_outb(st, 0, 0x01, 200); /* no change: no entry */
    vpp_drive(st, 10, 0);       /* outside changes are not logged */
    vpp_outb(st, 0, 0x03, 300);
    size_t n = vpp_log_read(st, 0, e, 8, &first);
    CHECK_EQ_INT(n, 2);
    CHECK_EQ_INT(first, 0);
    CHECK_EQ_INT(e[0].t_ns, 100);
    CHECK_EQ_INT((e[0].pins >> 2) & 0xff, 0x01);
    CHECK_EQ_INT(e[1].t_ns, 300);
    CHECK_EQ_INT((e[1].pins >> 10) & 1, 0); /* levels include the outside */
    CHECK_EQ_INT(vpp_log_read(st, 1, e, 8, &first), 1);
    CHECK_EQ_INT(first, 1);
    vpp_log_clear(st);
    CHECK_EQ_INT(vpp_log_read(st, 0, e, 8, &first), 0);
    vpp_outb(st, 0, 0x07, 400);
    CHECK_EQ_INT(vpp_log_read(st, 0, e, 8, &first), 1);
    CHECK_EQ_INT(first, 2);
    CHECK_EQ_INT(e[0].t_ns, 400);
    /* the ring keeps the last VPP_LOG_LEN entries */
    for (unsigned i = 0; i < VPP_LOG_LEN + 5; i++)
        vpp_outb(st, 0, (uint8_t)(i & 1 ? 0xf0 : 0x0f), 1000 + i);
    static struct vpp_log_entry big[VPP_LOG_LEN];
    n = vpp_log_read(st, 0, big, VPP_LOG_LEN, &first);
    CHECK_EQ_INT(n, VPP_LOG_LEN);
    CHECK_EQ_INT(first, vpp_log_head(st) - VPP_LOG_LEN);
    CHECK_EQ_INT(big[n - 1].t_ns, 1000 + VPP_LOG_LEN + 4);
    vpp_counters_reset(st);
    CHECK_EQ_INT(st->writes[VPP_REG_DATA], 0);
    vpp_close(st);
}

static void test_claim(void)
{
    char path[128], err[600];
    struct vpp_state *st = make("claim", 0, path, sizeof(path));
    CHECK_EQ_INT(vpp_claim(st, getpid(), path, err, sizeof(err)), 0);
    CHECK_EQ_INT(vpp_claim(st, getpid(), path, err, sizeof(err)), -EBUSY);
    CHECK(strstr(err, "claimed by this process") != NULL);
    vpp_release(st, getppid()); /* not the owner: no effect */
    CHECK_EQ_INT(st->owner_pid, getpid());
    vpp_release(st, getpid());
    CHECK_EQ_INT(st->owner_pid, 0);
    /* a live other process holds it */
    CHECK_EQ_INT(vpp_claim(st, getppid(), path, err, sizeof(err)), 0);
    CHECK_EQ_INT(vpp_claim(st, getpid(), path, err, sizeof(err)), -EBUSY);
    CHECK(strstr(err, "is busy (claimed by process") != NULL);
    vpp_release(st, getppid());
    /* a dead owner's claim is taken over */
    pid_t child = fork();
    if (child == 0)
        _exit(0);
    waitpid(child, NULL, 0);
    st->owner_pid = child;
    CHECK_EQ_INT(vpp_claim(st, getpid(), path, err, sizeof(err)), 0);
    CHECK_EQ_INT(st->owner_pid, getpid());
    vpp_close(st);
}

static void test_file(void)
{
    char path[128], err[600];
    struct vpp_state *st;
    snprintf(path, sizeof(path), "%s/missing", dir);
    CHECK_EQ_INT(vpp_open(path, &st, err, sizeof(err)), -ENOENT);
    CHECK(strstr(err, "vparport create") != NULL);
    snprintf(path, sizeof(path), "%s/notaport", dir);
    FILE *f = fopen(path, "w");
    fputs("hello", f);
    fclose(f);
    CHECK_EQ_INT(vpp_open(path, &st, err, sizeof(err)), -EINVAL);
    CHECK(strstr(err, "not a virtual parallel port") != NULL);
    CHECK_EQ_INT(vpp_remove(path, err, sizeof(err)), -EINVAL); /* never removed */
    CHECK_EQ_INT(access(path, F_OK), 0);
    snprintf(path, sizeof(path), "%s/twice", dir);
    CHECK_EQ_INT(vpp_create(path, 0, 0, err, sizeof(err)), 0);
    CHECK_EQ_INT(vpp_create(path, 0, 0, err, sizeof(err)), -EEXIST);
    CHECK_EQ_INT(vpp_create(path, VPP_OPT_ECR, 1, err, sizeof(err)), 0);
    CHECK_EQ_INT(vpp_open(path, &st, err, sizeof(err)), 0);
    CHECK_EQ_INT(st->options, VPP_OPT_ECR);
    vpp_close(st);
    CHECK_EQ_INT(vpp_remove(path, err, sizeof(err)), 0);
    CHECK_EQ_INT(access(path, F_OK), -1);
    char p2[128];
    CHECK_EQ_INT(vpp_path("abc", p2, sizeof(p2)), 0);
    CHECK_EQ_STR(p2, "/dev/shm/vparport.abc");
    CHECK_EQ_INT(vpp_path("", p2, sizeof(p2)), -EINVAL);
}

int main(void)
{
    snprintf(dir, sizeof(dir), "/tmp/vppXXXXXX");
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    RUN(test_power_on);
    RUN(test_status_bits);
    RUN(test_control_inversions_and_oc);
    RUN(test_control_push_pull);
    RUN(test_data_direction);
    RUN(test_ecr);
    RUN(test_log);
    RUN(test_claim);
    RUN(test_file);
    char cmd[128];
    snprintf(cmd, sizeof(cmd), "rm -rf %s", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", dir);
    return check_summary();
}
