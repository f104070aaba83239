/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Unit tests of libhal (hal.h, hal_query.h, rtapi shmem) in one process.
 * The reference for each rule is the HAL documentation (seeds) and
 * LinuxCNC 2.9's observed behaviour, as cited in the checks.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "hal.h"
#include "hal_priv.h"
#include "hal_query.h"

static int created_threads;
static int hook_created(hal_thread_t *t)
{
    (void)t;
    created_threads++;
    return 0;
}
static void hook_deleting(hal_thread_t *t)
{
    (void)t;
    created_threads--;
}
static const hal_thread_hooks_t hooks = {hook_created, hook_deleting};

typedef struct {
    hal_bit_t *b_in, *b_out, *b_io, *b_out2;
    hal_float_t *f_in, *f_out;
    hal_s32_t *s_in;
    hal_u32_t *u_in;
    hal_s64_t *l_in;
    hal_u64_t *ul_in;
    hal_float_t prm_rw, prm_ro;
    hal_s32_t prm_s32;
} pins_t;

static int comp;
static pins_t *P;

static int counts(void)
{
    /* a fingerprint of the object counts */
    return hal_hdr->active_pins * 1000000 + hal_hdr->active_sigs * 10000 +
           hal_hdr->active_params * 100 + hal_hdr->active_comps;
}

static void test_components(void)
{
    comp = hal_init("unitcomp");
    CHECK(comp > 0);
    CHECK(hal_init("unitcomp") == -EEXIST);
    CHECK(hal_init("a_name_that_is_much_too_long_for_hal_0123456789abcdef") == -EINVAL);
    CHECK(hal_init("") == -EINVAL);
    CHECK_EQ_STR(hal_comp_name(comp), "unitcomp");
    CHECK(hal_q_component_exists("unitcomp"));
    CHECK(!hal_q_component_ready("unitcomp"));
    hal_q_comp_t c;
    CHECK_EQ_INT(hal_q_comp("unitcomp", &c), 0);
    CHECK_EQ_INT(c.realtime, 0);
    CHECK_EQ_INT(c.pid, getpid());
}

static void test_pins(void)
{
    P = hal_malloc(sizeof(*P));
    CHECK(P != NULL);
    CHECK_EQ_INT(hal_pin_bit_new("u.b-in", HAL_IN, &P->b_in, comp), 0);
    CHECK_EQ_INT(hal_pin_bit_new("u.b-out", HAL_OUT, &P->b_out, comp), 0);
    CHECK_EQ_INT(hal_pin_bit_new("u.b-io", HAL_IO, &P->b_io, comp), 0);
    CHECK_EQ_INT(hal_pin_bit_newf(HAL_OUT, &P->b_out2, comp, "u.b-out%d", 2), 0);
    CHECK_EQ_INT(hal_pin_float_new("u.f-in", HAL_IN, &P->f_in, comp), 0);
    CHECK_EQ_INT(hal_pin_float_new("u.f-out", HAL_OUT, &P->f_out, comp), 0);
    CHECK_EQ_INT(hal_pin_s32_new("u.s-in", HAL_IN, &P->s_in, comp), 0);
    CHECK_EQ_INT(hal_pin_u32_new("u.u-in", HAL_IN, &P->u_in, comp), 0);
    CHECK_EQ_INT(hal_pin_s64_new("u.l-in", HAL_IN, &P->l_in, comp), 0);
    CHECK_EQ_INT(hal_pin_u64_new("u.ul-in", HAL_IN, &P->ul_in, comp), 0);
    int before = counts();
    /* bad input changes nothing */
    CHECK(hal_pin_bit_new("u.b-in", HAL_IN, &P->b_in, comp) == -EEXIST);
    static hal_bit_t *not_in_shm;
    CHECK(hal_pin_bit_new("u.x", HAL_IN, &not_in_shm, comp) == -EINVAL);
    CHECK(hal_pin_new("u.y", (hal_type_t)99, HAL_IN, (void **)&P->b_in, comp) == -EINVAL);
    CHECK(hal_pin_new("u.y", HAL_BIT, (hal_pin_dir_t)7, (void **)&P->b_in, comp) == -EINVAL);
    CHECK(hal_pin_bit_new("u.y", HAL_IN, &P->b_in, 9999) < 0);
    CHECK(hal_pin_bit_newf(HAL_IN, &P->b_in, comp, "%s", "a_pin_name_that_is_far_too_long_to_be_a_hal_name_xyz") < 0);
    CHECK_EQ_INT(counts(), before);
    /* unconnected pins point at their own dummy: writes read back */
    *P->f_out = 2.5;
    *P->s_in = -3;
    char buf[64];
    CHECK_EQ_INT(hal_q_getp("u.f-out", buf, sizeof(buf), NULL, NULL, 0), 0);
    CHECK_EQ_STR(buf, "2.5");
    CHECK_EQ_INT(hal_q_getp("u.s-in", buf, sizeof(buf), NULL, NULL, 0), 0);
    CHECK_EQ_STR(buf, "-3");
    CHECK_EQ_INT(hal_param_float_new("u.prm-rw", HAL_RW, &P->prm_rw, comp), 0);
    CHECK_EQ_INT(hal_param_float_new("u.prm-ro", HAL_RO, &P->prm_ro, comp), 0);
    CHECK_EQ_INT(hal_param_s32_newf(HAL_RW, &P->prm_s32, comp, "u.prm-%s", "s32"), 0);
    CHECK(hal_param_float_new("u.prm-rw", HAL_RW, &P->prm_rw, comp) == -EEXIST);
    CHECK_EQ_INT(hal_ready(comp), 0);
    CHECK(hal_q_component_ready("unitcomp"));
    /* no new objects after hal_ready (LinuxCNC rule) */
    CHECK(hal_pin_bit_new("u.late", HAL_IN, &P->b_in, comp) < 0);
}

static void test_link_rules(void)
{
    CHECK_EQ_INT(hal_signal_new("sb", HAL_BIT), 0);
    CHECK_EQ_INT(hal_signal_new("sf", HAL_FLOAT), 0);
    CHECK(hal_signal_new("sb", HAL_BIT) == -EEXIST);
    CHECK(hal_signal_new("bad", (hal_type_t)42) == -EINVAL);
    /* An OUT pin's old value is not copied into the signal (seeds). */
    CHECK_EQ_INT(hal_link("u.f-out", "sf"), 0);
    char buf[64];
    hal_q_gets("sf", buf, sizeof(buf), NULL, NULL, 0);
    CHECK_EQ_STR(buf, "0");
    /* the pin now writes the signal */
    *P->f_out = 4.25;
    hal_q_gets("sf", buf, sizeof(buf), NULL, NULL, 0);
    CHECK_EQ_STR(buf, "4.25");
    CHECK_EQ_INT(hal_link("u.f-in", "sf"), 0);
    CHECK(*P->f_in == 4.25);
    CHECK_EQ_INT(hal_q_pin_has_writer("u.f-in"), 1);
    CHECK_EQ_INT(hal_q_pin_has_writer("u.s-in"), 0);
    CHECK(hal_q_pin_has_writer("no.such") == -ENOENT);
    int before = counts();
    /* type mismatch */
    CHECK(hal_link("u.b-in", "sf") == -EINVAL);
    /* one writer */
    CHECK_EQ_INT(hal_link("u.b-out", "sb"), 0);
    CHECK(hal_link("u.b-out2", "sb") == -EINVAL);
    /* IO pins only when there is no OUT pin */
    CHECK(hal_link("u.b-io", "sb") == -EINVAL);
    CHECK(hal_link("no.pin", "sb") == -EINVAL);
    CHECK(hal_link("u.b-in", "nosig") == -EINVAL);
    CHECK_EQ_INT(counts(), before);
    hal_q_sig_t s;
    CHECK_EQ_INT(hal_q_sig("sb", &s), 0);
    CHECK_EQ_INT(s.writers, 1);
    CHECK_EQ_INT(s.bidirs, 0);
    /* linking a pin to the signal it is on is a no-op; to another fails */
    CHECK_EQ_INT(hal_link("u.b-out", "sb"), 0);
    CHECK_EQ_INT(hal_signal_new("sb2", HAL_BIT), 0);
    CHECK(hal_link("u.b-out", "sb2") == -EINVAL);
    /* IO + IO is fine, and an OUT pin is then refused */
    CHECK_EQ_INT(hal_link("u.b-io", "sb2"), 0);
    CHECK(hal_link("u.b-out2", "sb2") == -EINVAL);
    CHECK_EQ_INT(hal_q_sig("sb2", &s), 0);
    CHECK_EQ_INT(s.bidirs, 1);
    /* sets refuses a signal with a writer, accepts one without */
    char err[128];
    CHECK(hal_q_sets("sb", "1", err, sizeof(err)) == -EPERM);
    CHECK_EQ_STR(err, "signal 'sb' already has writer(s)");
    CHECK_EQ_INT(hal_q_sets("sb2", "TRUE", err, sizeof(err)), 0);
    CHECK(*P->b_io == 1);
    /* unlink keeps the signal's value in the pin (LinuxCNC 2.9) */
    CHECK_EQ_INT(hal_unlink("u.b-io"), 0);
    CHECK(*P->b_io == 1);
    CHECK_EQ_INT(hal_q_sets("sb2", "0", err, sizeof(err)), 0);
    CHECK(*P->b_io == 1);
    /* first IN pin of an empty signal seeds it (LinuxCNC 2.9) */
    *P->s_in = 77;
    CHECK_EQ_INT(hal_signal_new("ss", HAL_S32), 0);
    CHECK_EQ_INT(hal_link("u.s-in", "ss"), 0);
    hal_q_gets("ss", buf, sizeof(buf), NULL, NULL, 0);
    CHECK_EQ_STR(buf, "77");
    /* setp refuses a connected pin and an OUT pin */
    CHECK(hal_q_setp("u.s-in", "1", err, sizeof(err)) == -EPERM);
    CHECK_EQ_STR(err, "pin 'u.s-in' is connected to a signal");
    CHECK(hal_q_setp("u.b-out2", "1", err, sizeof(err)) == -EPERM);
    CHECK_EQ_STR(err, "pin 'u.b-out2' is not writable");
    /* deleting a signal unlinks its pins, which keep the value */
    CHECK_EQ_INT(hal_signal_delete("ss"), 0);
    CHECK(*P->s_in == 77);
    CHECK_EQ_INT(hal_q_setp("u.s-in", "5", err, sizeof(err)), 0);
    CHECK(*P->s_in == 5);
    CHECK(hal_signal_delete("ss") == -EINVAL);
}

static void test_values(void)
{
    hal_data_u v;
    CHECK_EQ_INT(hal_q_parse_value(HAL_BIT, "1", &v), 0);
    CHECK(v.b == 1);
    CHECK_EQ_INT(hal_q_parse_value(HAL_BIT, "true", &v), 0);
    CHECK_EQ_INT(hal_q_parse_value(HAL_BIT, "FALSE", &v), 0);
    CHECK(v.b == 0);
    CHECK_EQ_INT(hal_q_parse_value(HAL_BIT, "2", &v), -EINVAL);
    CHECK_EQ_INT(hal_q_parse_value(HAL_BIT, "0x1", &v), -EINVAL);
    CHECK_EQ_INT(hal_q_parse_value(HAL_BIT, "", &v), -EINVAL);
    CHECK_EQ_INT(hal_q_parse_value(HAL_S32, "-2147483648", &v), 0);
    CHECK_EQ_INT(v.s, INT32_MIN);
    CHECK_EQ_INT(hal_q_parse_value(HAL_S32, "2147483648", &v), -ERANGE);
    CHECK_EQ_INT(hal_q_parse_value(HAL_S32, "0x7fffffff", &v), 0);
    CHECK_EQ_INT(hal_q_parse_value(HAL_S32, "1.5", &v), -EINVAL);
    CHECK_EQ_INT(hal_q_parse_value(HAL_U32, "4294967295", &v), 0);
    CHECK_EQ_INT(v.u, UINT32_MAX);
    CHECK_EQ_INT(hal_q_parse_value(HAL_U32, "4294967296", &v), -ERANGE);
    CHECK_EQ_INT(hal_q_parse_value(HAL_U32, "-1", &v), -ERANGE);
    CHECK_EQ_INT(hal_q_parse_value(HAL_U32, "-x", &v), -EINVAL);
    CHECK_EQ_INT(hal_q_parse_value(HAL_S64, "-9223372036854775808", &v), 0);
    CHECK(v.ls == INT64_MIN);
    CHECK_EQ_INT(hal_q_parse_value(HAL_S64, "9223372036854775808", &v), -ERANGE);
    CHECK_EQ_INT(hal_q_parse_value(HAL_U64, "18446744073709551615", &v), 0);
    CHECK(v.lu == UINT64_MAX);
    CHECK_EQ_INT(hal_q_parse_value(HAL_U64, "-1", &v), -ERANGE);
    CHECK_EQ_INT(hal_q_parse_value(HAL_FLOAT, "1e400", &v), -ERANGE);
    CHECK_EQ_INT(hal_q_parse_value(HAL_FLOAT, "0x10", &v), 0);
    CHECK_NEAR(v.f, 16.0, 0);
    CHECK_EQ_INT(hal_q_parse_value(HAL_FLOAT, "1.5 x", &v), -EINVAL);
    CHECK_EQ_INT(hal_q_parse_value((hal_type_t)99, "1", &v), -EINVAL);
    char buf[64];
    v.f = 123456789.0;
    hal_q_format_value(HAL_FLOAT, &v, buf, sizeof(buf));
    CHECK_EQ_STR(buf, "1.234568e+08"); /* LinuxCNC: %.7g */
    v.u = 31;
    hal_q_format_value(HAL_U32, &v, buf, sizeof(buf));
    CHECK_EQ_STR(buf, "31");
    v.b = 1;
    hal_q_format_value(HAL_BIT, &v, buf, sizeof(buf));
    CHECK_EQ_STR(buf, "TRUE");
    char err[128];
    CHECK(hal_q_setp("u.prm-s32", "1.5", err, sizeof(err)) == -EINVAL);
    CHECK_EQ_STR(err, "value '1.5' invalid for S32");
    CHECK(hal_q_setp("u.prm-s32", "99999999999", err, sizeof(err)) == -ERANGE);
    CHECK(hal_q_setp("u.prm-ro", "1", err, sizeof(err)) == -EPERM);
    CHECK_EQ_STR(err, "param 'u.prm-ro' is not writable");
    CHECK(hal_q_setp("nothing", "1", err, sizeof(err)) == -ENOENT);
    CHECK_EQ_STR(err, "parameter or pin 'nothing' not found");
    CHECK_EQ_INT(hal_param_float_set("u.prm-rw", 3.5), 0);
    CHECK(P->prm_rw == 3.5);
    CHECK(hal_param_float_set("u.prm-ro", 3.5) == -EINVAL);
    CHECK(hal_param_s32_set("u.prm-rw", 1) == -EINVAL); /* type mismatch */
    CHECK(hal_param_s32_set("u.prm-s32", 1L << 40) == -EINVAL);
    CHECK_EQ_INT(hal_param_s32_set("u.prm-s32", -9), 0);
    CHECK(P->prm_s32 == -9);
    hal_type_t t;
    CHECK_EQ_INT(hal_q_getp("u.l-in", NULL, 0, &t, NULL, 0), 0);
    CHECK_EQ_INT(t, HAL_S64);
    CHECK(hal_q_type_from_name("u64") == HAL_U64);
    CHECK(hal_q_type_from_name("port") == HAL_TYPE_UNSPECIFIED);
}

static void test_alias(void)
{
    CHECK_EQ_INT(hal_pin_alias("u.f-in", "myalias"), 0);
    hal_q_pin_t p;
    CHECK_EQ_INT(hal_q_pin("myalias", &p), 0);
    CHECK_EQ_STR(p.original, "u.f-in");
    CHECK_EQ_INT(hal_q_pin("u.f-in", &p), 0); /* the old name still works */
    CHECK_EQ_STR(p.name, "myalias");
    CHECK(hal_pin_alias("u.f-out", "myalias") == -EINVAL); /* in use */
    CHECK(hal_pin_alias("nopin", "x") == -EINVAL);
    CHECK_EQ_INT(hal_pin_alias("myalias", NULL), 0);
    CHECK(hal_q_pin("myalias", &p) == -ENOENT);
    CHECK_EQ_INT(hal_param_alias("u.prm-rw", "pa"), 0);
    CHECK_EQ_INT(hal_q_param("pa", &p), 0);
    CHECK_EQ_INT(hal_param_alias("pa", ""), 0);
    CHECK_EQ_INT(hal_hdr->active_aliases, 0);
}

static int collect(const char *name, void *ctx)
{
    char *s = ctx;
    strcat(s, name);
    strcat(s, " ");
    return 0;
}

static void test_foreach(void)
{
    char s[1024] = "";
    CHECK_EQ_INT(hal_q_foreach(HAL_Q_PIN, "u.b", collect, s), 4);
    CHECK_EQ_STR(s, "u.b-in u.b-io u.b-out u.b-out2 ");
    s[0] = '\0';
    CHECK_EQ_INT(hal_q_foreach(HAL_Q_PIN, "*-in", collect, s), 6);
    CHECK_EQ_STR(s, "u.b-in u.f-in u.l-in u.s-in u.u-in u.ul-in ");
    s[0] = '\0';
    hal_q_foreach(HAL_Q_SIG, NULL, collect, s);
    CHECK_EQ_STR(s, "sb sb2 sf ");
    CHECK(hal_q_match("and2.0", "and2.0.in0"));
    CHECK(hal_q_match("*.in?", "and2.0.in0"));
    CHECK(!hal_q_match("or2", "and2.0.in0"));
}

static void fn_a(void *arg, long period)
{
    (void)arg;
    (void)period;
}

static void test_functs_threads(void)
{
    /* Pretend to be rtapi_app: RT components, threads via hooks. */
    hal_priv_set_realtime_host(1);
    hal_priv_set_thread_hooks(&hooks);
    int rt = hal_init("rtcomp");
    CHECK(rt > 0);
    hal_q_comp_t c;
    hal_q_comp("rtcomp", &c);
    CHECK_EQ_INT(c.realtime, 1);
    CHECK_EQ_INT(hal_export_funct("rt.a", fn_a, NULL, 1, 0, rt), 0);
    CHECK_EQ_INT(hal_export_funct("rt.b", fn_a, NULL, 0, 0, rt), 0);
    CHECK_EQ_INT(hal_export_funct("rt.c", fn_a, NULL, 0, 1, rt), 0);
    CHECK(hal_export_funct("rt.a", fn_a, NULL, 0, 0, rt) == -EEXIST);
    CHECK(hal_export_funct("rt.z", fn_a, NULL, 0, 0, comp) < 0); /* user comp */
    /* LinuxCNC 2.9: NAME.time pin, NAME.tmax and NAME.tmax-increased params */
    CHECK_EQ_INT(hal_q_pin("rt.a.time", NULL), 0);
    CHECK_EQ_INT(hal_q_param("rt.a.tmax", NULL), 0);
    CHECK_EQ_INT(hal_q_param("rt.a.tmax-increased", NULL), 0);
    hal_ready(rt);
    CHECK_EQ_INT(hal_create_thread("fast", 100000, 0), 0);
    CHECK_EQ_INT(hal_create_thread("slow", 250000, 1), 0);
    CHECK(hal_create_thread("slow", 1000000, 1) == -EEXIST);
    /* faster than the first thread: refused (LinuxCNC) */
    CHECK(hal_create_thread("faster", 50000, 1) == -EINVAL);
    CHECK_EQ_INT(created_threads, 2);
    hal_q_thread_t t;
    CHECK_EQ_INT(hal_q_thread("slow", &t), 0);
    CHECK_EQ_INT(t.period, 300000); /* rounded to a multiple of 100000 */
    CHECK(hal_q_comp("__slow", NULL) == 0);
    CHECK(hal_q_pin("slow.time", NULL) == 0);
    CHECK(hal_q_param("slow.tmax", NULL) == 0);
    /* fp function in a non-fp thread */
    CHECK(hal_add_funct_to_thread("rt.a", "fast", -1) == -EINVAL);
    CHECK_EQ_INT(hal_add_funct_to_thread("rt.a", "slow", -1), 0);
    CHECK_EQ_INT(hal_add_funct_to_thread("rt.b", "slow", 1), 0);   /* b a */
    CHECK(hal_add_funct_to_thread("rt.c", "slow", 4) == -EINVAL);  /* too high */
    CHECK(hal_add_funct_to_thread("rt.c", "slow", -4) == -EINVAL); /* too low */
    CHECK(hal_add_funct_to_thread("rt.c", "slow", 0) == -EINVAL);
    CHECK_EQ_INT(hal_add_funct_to_thread("rt.c", "slow", -2), 0);  /* b c a */
    CHECK_EQ_INT(hal_add_funct_to_thread("rt.c", "fast", 1), 0);   /* reentrant */
    CHECK(hal_add_funct_to_thread("rt.b", "fast", 1) == -EINVAL);  /* one thread only */
    CHECK(hal_add_funct_to_thread("rt.x", "fast", 1) == -EINVAL);
    CHECK(hal_add_funct_to_thread("rt.b", "nothread", 1) == -EINVAL);
    char names[8][HAL_NAME_LEN + 1];
    CHECK_EQ_INT(hal_q_thread_functs("slow", names, 8), 3);
    CHECK_EQ_STR(names[0], "rt.b");
    CHECK_EQ_STR(names[1], "rt.c");
    CHECK_EQ_STR(names[2], "rt.a");
    hal_q_funct_t f;
    hal_q_funct("rt.c", &f);
    CHECK_EQ_INT(f.users, 2);
    CHECK_EQ_INT(hal_del_funct_from_thread("rt.c", "slow"), 0);
    CHECK(hal_del_funct_from_thread("rt.c", "slow") == -EINVAL);
    CHECK_EQ_INT(hal_q_thread_functs("slow", names, 8), 2);
    /* removing the component takes its functions out of the threads */
    CHECK_EQ_INT(hal_exit(rt), 0);
    CHECK_EQ_INT(hal_q_thread_functs("slow", names, 8), 0);
    CHECK_EQ_INT(hal_q_thread_functs("fast", names, 8), 0);
    CHECK(hal_q_pin("rt.a.time", NULL) == -ENOENT);
    CHECK_EQ_INT(hal_thread_delete("slow"), 0);
    CHECK_EQ_INT(hal_thread_delete("fast"), 0);
    CHECK(hal_thread_delete("fast") == -EINVAL);
    CHECK_EQ_INT(created_threads, 0);
    CHECK(hal_q_comp("__slow", NULL) == -ENOENT);
    hal_priv_set_realtime_host(0);
    /* outside rtapi_app threads cannot be created */
    CHECK(hal_create_thread("t", 1000000, 1) == -EPERM);
}

static void test_lock(void)
{
    CHECK_EQ_INT(hal_set_lock(HAL_LOCK_CONFIG), 0);
    CHECK(hal_signal_new("locked", HAL_BIT) == -EPERM);
    CHECK(hal_link("u.b-in", "sb") == -EPERM);
    CHECK(hal_unlink("u.f-in") == -EPERM);
    CHECK_EQ_INT(hal_set_lock(HAL_LOCK_LOAD), 0);
    CHECK(hal_init("locked") == -EPERM);
    CHECK_EQ_INT(hal_set_lock(HAL_LOCK_RUN), 0);
    CHECK(hal_start_threads() == -EPERM);
    CHECK_EQ_INT(hal_set_lock(HAL_LOCK_NONE), 0);
    CHECK_EQ_INT(hal_get_lock(), 0);
}

static void test_memory(void)
{
    CHECK(hal_malloc(0) == NULL);
    CHECK(hal_malloc(1L << 40) == NULL);
    void *a = hal_malloc(3), *b = hal_malloc(8);
    CHECK(a != NULL && b != NULL);
    CHECK(((uintptr_t)b & 7) == 0);
    /* blocks of 16 bytes or more are aligned for any type, as malloc's */
    for (long n = 16; n <= 40; n += 8) {
        void *c = hal_malloc(n);
        CHECK(c != NULL && ((uintptr_t)c & 15) == 0);
        hal_malloc(3);
    }
    unsigned long off = hal_q_shm_offset(b);
    CHECK(off != 0);
    CHECK(hal_q_shm_ptr(off) == b);
    static int not_shared;
    CHECK(hal_q_shm_offset(&not_shared) == 0);
    CHECK(hal_q_shm_ptr(0) == NULL);
}

static void test_shmem_blocks(void)
{
    int h1 = rtapi_shmem_new(0x1234, 1, 4096);
    CHECK(h1 > 0);
    int h2 = rtapi_shmem_new(0x1234, 2, 4096);
    CHECK(h2 == h1);
    void *p1 = NULL, *p2 = NULL;
    CHECK_EQ_INT(rtapi_shmem_getptr(h1, &p1), 0);
    CHECK_EQ_INT(rtapi_shmem_getptr(h2, &p2), 0);
    CHECK(p1 == p2 && p1 != NULL);
    CHECK(rtapi_shmem_new(0x1234, 3, 8192) == -EINVAL); /* other size */
    CHECK(rtapi_shmem_new(0x1235, 3, 0) == -EINVAL);
    CHECK(rtapi_shmem_getptr(99, &p1) == -EINVAL);
    CHECK_EQ_INT(rtapi_shmem_delete(h1, 1), 0);
    CHECK_EQ_INT(rtapi_shmem_delete(h2, 2), 0);
    CHECK(rtapi_shmem_delete(h2, 2) == -EINVAL);
}

static void test_exit_cleans(void)
{
    int before_sigs = hal_hdr->active_sigs;
    CHECK_EQ_INT(hal_exit(comp), 0);
    CHECK(hal_exit(comp) == -EINVAL);
    CHECK(hal_q_pin("u.f-in", NULL) == -ENOENT);
    /* signals stay, without readers/writers */
    CHECK_EQ_INT(hal_hdr->active_sigs, before_sigs);
    hal_q_sig_t s;
    CHECK_EQ_INT(hal_q_sig("sf", &s), 0);
    CHECK_EQ_INT(s.readers + s.writers + s.bidirs, 0);
    CHECK_EQ_INT(hal_hdr->active_pins, 0);
    CHECK_EQ_INT(hal_hdr->active_params, 0);
}

/* Several processes create, link, unlink and delete at once: afterwards the
 * lists, counters and indexes must agree (one lock, no corruption). */
static void test_concurrent_processes(void)
{
    enum { NPROC = 4, ITER = 300 };
    pid_t pids[NPROC];
    for (int p = 0; p < NPROC; p++) {
        pids[p] = fork();
        if (pids[p] == 0) {
            char cname[32];
            snprintf(cname, sizeof(cname), "child%d", p);
            int id = hal_init(cname);
            hal_float_t **pin = hal_malloc(sizeof(*pin));
            char pname[48], sname[48];
            snprintf(pname, sizeof(pname), "child%d.in", p);
            if (id < 0 || pin == NULL || hal_pin_float_new(pname, HAL_IN, pin, id) != 0)
                _exit(2);
            hal_ready(id);
            for (int i = 0; i < ITER; i++) {
                snprintf(sname, sizeof(sname), "c%d-s%d", p, i % 7);
                if (hal_signal_new(sname, HAL_FLOAT) != 0)
                    _exit(3);
                if (hal_link(pname, sname) != 0)
                    _exit(4);
                char err[128];
                if (hal_q_sets(sname, "1.5", err, sizeof(err)) != 0 || **pin != 1.5)
                    _exit(5);
                if (hal_unlink(pname) != 0 || hal_signal_delete(sname) != 0)
                    _exit(6);
            }
            hal_exit(id);
            _exit(0);
        }
    }
    int ok = 1;
    for (int p = 0; p < NPROC; p++) {
        int st;
        waitpid(pids[p], &st, 0);
        if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) {
            fprintf(stderr, "child %d: status %d\n", p, st);
            ok = 0;
        }
    }
    CHECK(ok);
    int nsig = 0;
    for (hal_off_t off = hal_hdr->sig_list; off; off = ((hal_sig_t *)SHMPTR(off))->next)
        nsig++;
    CHECK_EQ_INT(nsig, hal_hdr->active_sigs);
    for (int p = 0; p < NPROC; p++) {
        char cname[32];
        snprintf(cname, sizeof(cname), "child%d", p);
        CHECK(!hal_q_component_exists(cname));
    }
    CHECK(hal_q_sig("c0-s1", NULL) == -ENOENT);
}

/* A process that dies holding the HAL mutex does not block the others
 * (robust mutex). */
static void test_dead_lock_holder(void)
{
    pid_t pid = fork();
    if (pid == 0) {
        hal_priv_lock();
        _exit(0);
    }
    int st;
    waitpid(pid, &st, 0);
    CHECK_EQ_INT(hal_signal_new("after-crash", HAL_BIT), 0);
    CHECK_EQ_INT(hal_signal_delete("after-crash"), 0);
}

/* The runtime directory is private and checked; the log never follows a
 * planted link. */
static void test_runtime_dir(void)
{
    char base[] = "/tmp/hal-unit-rtdir-XXXXXX";
    CHECK(mkdtemp(base) != NULL);
    char *old = getenv("XDG_RUNTIME_DIR") ? strdup(getenv("XDG_RUNTIME_DIR")) : NULL;
    setenv("XDG_RUNTIME_DIR", base, 1);
    char dir[256], want[300], path[512];
    snprintf(want, sizeof(want), "%s/hm2hal", base);
    CHECK_EQ_INT(hal_priv_runtime_dir(dir, sizeof(dir), 1), 0);
    CHECK_EQ_STR(dir, want);
    struct stat st;
    CHECK(lstat(dir, &st) == 0 && S_ISDIR(st.st_mode) && (st.st_mode & 0777) == 0700);
    /* a log path planted as a symbolic link is not followed */
    snprintf(path, sizeof(path), "%s/%s.log", dir, hal_priv_shm_name() + 1);
    CHECK(symlink("/tmp/hal-unit-victim", path) == 0);
    CHECK(hal_priv_open_log(path, sizeof(path)) < 0);
    CHECK(access("/tmp/hal-unit-victim", F_OK) != 0);
    unlink(path);
    int fd = hal_priv_open_log(path, sizeof(path));
    CHECK(fd >= 0);
    if (fd >= 0)
        close(fd);
    CHECK(lstat(path, &st) == 0 && S_ISREG(st.st_mode) && (st.st_mode & 0777) == 0600);
    unlink(path);
    /* a directory others may use is refused, and so is a link to one */
    chmod(dir, 0755);
    CHECK_EQ_INT(hal_priv_runtime_dir(dir, sizeof(dir), 1), -EPERM);
    rmdir(want);
    CHECK(symlink("/tmp", want) == 0);
    CHECK_EQ_INT(hal_priv_runtime_dir(dir, sizeof(dir), 1), -EPERM);
    unlink(want);
    rmdir(base);
    if (old != NULL) {
        setenv("XDG_RUNTIME_DIR", old, 1);
        free(old);
    } else {
        unsetenv("XDG_RUNTIME_DIR");
    }
}

/* A session with nothing left in it is removed by the last halcmd
 * (hal_priv_session_release); one with a signal is kept. */
static void test_session_release(void)
{
    char inst[64], seg[128];
    snprintf(inst, sizeof(inst), "unit-hal-rel-%d", (int)getpid());
    char *old = strdup(getenv("HAL_INSTANCE"));
    hal_priv_detach();
    setenv("HAL_INSTANCE", inst, 1);
    snprintf(seg, sizeof(seg), "/dev/shm%s", hal_priv_shm_name());
    int id = hal_init("relcomp");
    CHECK(id > 0);
    CHECK_EQ_INT(hal_priv_session_release(), 0); /* our component keeps it */
    CHECK_EQ_INT(hal_signal_new("keep-me", HAL_FLOAT), 0);
    CHECK_EQ_INT(hal_exit(id), 0);
    CHECK_EQ_INT(hal_priv_session_state(), HAL_SESSION_IDLE);
    CHECK_EQ_INT(hal_priv_session_release(), 0);
    CHECK(access(seg, F_OK) == 0);
    CHECK_EQ_INT(hal_signal_delete("keep-me"), 0);
    CHECK_EQ_INT(hal_priv_session_release(), 1);
    CHECK(access(seg, F_OK) != 0);
    CHECK_EQ_INT(hal_priv_session_state(), HAL_SESSION_NONE);
    setenv("HAL_INSTANCE", old, 1);
    free(old);
    CHECK_EQ_INT(hal_priv_attach(), 0);
}

int main(void)
{
    char inst[64];
    snprintf(inst, sizeof(inst), "unit-hal-%d", (int)getpid());
    setenv("HAL_INSTANCE", inst, 1);
    unsetenv("HAL_SIMCLOCK");
    hal_priv_session_destroy();
    RUN(test_components);
    RUN(test_pins);
    RUN(test_link_rules);
    RUN(test_values);
    RUN(test_alias);
    RUN(test_foreach);
    RUN(test_functs_threads);
    RUN(test_lock);
    RUN(test_memory);
    RUN(test_shmem_blocks);
    RUN(test_exit_cleans);
    RUN(test_concurrent_processes);
    RUN(test_dead_lock_holder);
    RUN(test_runtime_dir);
    RUN(test_session_release);
    hal_priv_session_destroy();
    return check_summary();
}
