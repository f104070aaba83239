/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_7i43 llio + the hostmot2 core (hm2hal with its test-double HAL):
 * a blank 7i43 model whose configured FPGA holds the build's generated
 * IDROM of 7i43 SV8 / SVST4_4 is reset, programmed from a .BIT file through
 * the CPLD and registered; the board's HAL objects, the per-period traffic
 * (one flush per direction on a batching port), and an EPP timeout that
 * sets io_error are checked.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "../check.h"
#include "../../../host/driver/hostmot2/hm2_hal.h"
#include "../driver/fake_hal.h"
#include "../driver/testlib.h"
#include "fakes.h"
#include "hm2_7i43_llio.h"

static struct periph P;
static struct pcport PC;
static epp_port_t PORT;
static struct hm2_7i43 B;
static struct tlog lg;
static char fwdir[256];
static uint8_t ebody[4096];

static void h7log(int level, const char *fmt, ...)
{
    (void)level, (void)fmt;
}
static long long h7now(void)
{
    static long long t;
    return t += 1000;
}

static int load_idrom(const char *fw)
{
    static struct hm2_image_llio im;
    char path[512], err[256];
    snprintf(path, sizeof(path), "%s/generated/7i43/%s/%s.idrom.hex", HM_BUILD_DIR, fw, fw);
    hm2_image_llio_init(&im, "x");
    int r = hm2_image_llio_load(&im, path, err, sizeof(err));
    if (r) {
        fprintf(stderr, "cannot load %s: %s\n", path, err);
        return r;
    }
    for (uint32_t a = 0; a < 0x10000; a += 4)
        periph_hm2_set(&P, a, hm2_image_get32(&im, a));
    return 0;
}

/* A .BIT file (spec §18) whose 'e' chunk the 7i43 model accepts. */
static void write_bitfile(const char *part)
{
    char dir[512], path[600];
    snprintf(dir, sizeof(dir), "%s/hm2", fwdir);
    mkdir(dir, 0700);
    snprintf(dir, sizeof(dir), "%s/hm2/7i43", fwdir);
    mkdir(dir, 0700);
    snprintf(path, sizeof(path), "%s/T.BIT", dir);
    FILE *f = fopen(path, "wb");
    static const uint8_t hdr[13] = {0, 9, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F, 0xF0, 0x0F, 0xF0, 0, 0, 1};
    fwrite(hdr, 1, 13, f);
    const char *txt[4] = {"T.ncd;UserID=0xFFFFFFFF", part, "2026/01/01", "12:00:00"};
    for (int i = 0; i < 4; i++) {
        size_t n = strlen(txt[i]) + 1;
        fputc('a' + i, f);
        fputc((int)(n >> 8), f);
        fputc((int)(n & 0xFF), f);
        fwrite(txt[i], 1, n, f);
    }
    for (size_t i = 0; i < sizeof(ebody); i++)
        ebody[i] = (uint8_t)(i * 13 + 5);
    fputc('e', f);
    uint32_t n = sizeof(ebody);
    fputc((int)(n >> 24), f), fputc((int)(n >> 16 & 0xFF), f), fputc((int)(n >> 8 & 0xFF), f),
        fputc((int)(n & 0xFF), f);
    fwrite(ebody, 1, sizeof(ebody), f);
    fclose(f);
}

static int bring_up(const char *fw, int batching, const char *part, int size400)
{
    char err[200];
    fake_hal_reset();
    tlog_clear(&lg);
    periph_init(&P, PERIPH_7I43);
    P.trace_on = 0;
    P.size400 = size400;
    P.expect_bits = ebody;
    P.expect_len = sizeof(ebody);
    pcport_init(&PC, &P);
    PC.log_on = 0;
    write_bitfile(part);
    if (load_idrom(fw))
        return -ENOENT;
    if (batching) {
        fake_batch_open(&PORT, &PC, 1);
    } else {
        static struct fake_raw fr;
        memset(&fr, 0, sizeof(fr));
        fr.pc = &PC;
        fr.base = 0x378;
        fr.base_hi = 0x778;
        struct epp_raw_io io = fake_raw_io(&fr);
        CHECK_EQ_INT(epp_raw_open(&PORT, &io, 0x378, 0x778, 1, err, sizeof(err)), 0);
    }
    int r = hm2_7i43_setup_board(&B, &PORT, 0, 1, 0, h7log, h7now);
    if (r)
        return r;
    B.llio.comp_id = 3;
    struct hm2_hal_options o = {{{0, 0, 0, 0}, fwdir}, tlog_sink, &lg};
    return hm2_register_opts(&B.llio, "firmware=hm2/7i43/T.BIT", &o);
}

static void test_sv8_raw(void)
{
    CHECK_EQ_INT(bring_up("SV8", 0, "3s400tq144", 1), 0);
    CHECK_EQ_INT(P.configured, 1);
    CHECK(tlog_contains(&lg, "Low Level init 0.15"));
    CHECK(tlog_contains(&lg, "registered"));
    CHECK(tlog_contains(&lg, "firmware hm2/7i43/T.BIT:"));
    CHECK(tlog_contains(&lg, "Part Name: 3s400tq144"));
    CHECK(fake_hal_find("hm2_7i43.0.read") != NULL);
    CHECK(fake_hal_find("hm2_7i43.0.write") != NULL);
    CHECK(fake_hal_find("hm2_7i43.0.read_gpio") == NULL); /* EPP: not thread-safe */
    CHECK(fake_hal_find("hm2_7i43.0.write_gpio") == NULL);
    CHECK(fake_hal_find("hm2_7i43.0.encoder.07.count") != NULL);
    CHECK(fake_hal_find("hm2_7i43.0.pwmgen.07.value") != NULL);
    CHECK(fake_hal_find("hm2_7i43.0.io_error") != NULL);
    /* a servo period, then an EPP timeout: io_error, LinuxCNC's message */
    fake_run("hm2_7i43.0.read", 1000000);
    fake_run("hm2_7i43.0.write", 1000000);
    hal_bit_t *ioe = (hal_bit_t *)fake_hal_find("hm2_7i43.0.io_error")->data;
    CHECK_EQ_INT(*ioe, 0);
    P.stall = 1;
    fake_run("hm2_7i43.0.read", 1000000);
    CHECK_EQ_INT(*ioe, 1);
    CHECK_EQ_INT(PC.timeout, 0);
    P.stall = 0;
    hm2_unregister_board(&B.llio);
    epp_port_close(&PORT);
}

static void test_svst4_4_batched(void)
{
    CHECK_EQ_INT(bring_up("SVST4_4", 1, "3s400tq144", 1), 0);
    CHECK(fake_hal_find("hm2_7i43.0.stepgen.03.position-cmd") != NULL);
    CHECK(fake_hal_find("hm2_7i43.0.encoder.03.count") != NULL);
    fake_run("hm2_7i43.0.read", 1000000);
    fake_run("hm2_7i43.0.write", 1000000);
    /* steady state: one flush per function */
    for (int k = 0; k < 3; k++) {
        uint64_t f0 = PORT.count.flushes;
        fake_run("hm2_7i43.0.read", 1000000);
        CHECK_EQ_INT(PORT.count.flushes - f0, 1);
        f0 = PORT.count.flushes;
        fake_run("hm2_7i43.0.write", 1000000);
        CHECK_EQ_INT(PORT.count.flushes - f0, 1);
    }
    hm2_unregister_board(&B.llio);
    epp_port_close(&PORT);
}

static void test_wrong_part(void)
{
    /* a 200K board refuses a bitstream built for the 400K part */
    CHECK_EQ_INT(bring_up("SV8", 0, "3s400tq144", 0), -EINVAL);
    CHECK(tlog_contains(&lg, "board has FPGA '3s200tq144', but the firmware in "
                             "hm2/7i43/T.BIT is for FPGA '3s400tq144'"));
    CHECK_EQ_INT(P.configured, 0);
    CHECK_EQ_INT(fake_hal_count("hm2_7i43.0", -1), 0);
    epp_port_close(&PORT);
}

int main(void)
{
    snprintf(fwdir, sizeof(fwdir), "/tmp/hm2-7i43-XXXXXX");
    if (!mkdtemp(fwdir)) {
        perror("mkdtemp");
        return 1;
    }
    RUN(test_sv8_raw);
    RUN(test_svst4_4_batched);
    RUN(test_wrong_part);
    char cmd[600];
    snprintf(cmd, sizeof(cmd), "rm -rf '%s'", fwdir);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", fwdir);
    return check_summary();
}
