/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_probe: IDROM validation (hm2_test patterns with LinuxCNC 2.9's exact
 * messages, 25+ further corruptions, read failures, a random-corruption
 * sweep), module descriptor acceptance, pin allocation and the pin report
 * of the seed's 5i20 example.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "../check.h"
#include "hm2/boards.h"
#include "test_patterns.h"
#include "testlib.h"

static struct hm2_image_llio im;
static struct tlog lg;

static hostmot2_t *probe(const char *config, int *err)
{
    tlog_clear(&lg);
    struct hm2_options opt = {{0, 0, 0, 0}, NULL};
    return hm2_probe(&im.llio, config, &opt, tlog_sink, &lg, err);
}

/* The probe must fail, print `want` exactly (with the board prefix) and
 * return a negative errno. */
static void expect_fail(const char *config, const char *want)
{
    int err = 0;
    hostmot2_t *hm2 = probe(config, &err);
    CHECK(hm2 == NULL);
    CHECK(err < 0);
    char full[600];
    snprintf(full, sizeof(full), "hm2/%s: %s", im.llio.name, want);
    int found = tlog_find(&lg, full, 0);
    CHECK(found >= 0);
    if (found < 0) {
        fprintf(stderr, "  wanted: %s\n", full);
        tlog_dump(&lg);
    }
    hm2_free(hm2);
}

/* ---- hm2_test patterns: messages captured from LinuxCNC 2.9.x
 * (`loadrt hostmot2 ...; loadrt hm2_test test_pattern=N` in halrun) ---- */
static const char *const linuxcnc_pattern_msg[HM2_TEST_NUM_PATTERNS] = {
    "invalid cookie, got 0x00000000, expected 0x55AACAFE",
    "invalid config name, got '\?\?\?\?\?\?\?\?', expected 'HOSTMOT2'",
    "invalid IDROM type 0, expected 2 or 3, aborting load",
    "invalid IDROM type 4660, expected 2 or 3, aborting load",
    "invalid IDROM PortWidth 0, this board has 24 pins per connector, aborting load",
    "invalid IDROM PortWidth 29, this board has 24 pins per connector, aborting load",
    "IDROM IOPorts is 0 but llio num_ioport_connectors is 1, driver and firmware are "
    "inconsistent, aborting driver load",
    "IDROM IOWidth is 99, but IDROM IOPorts is 1 and IDROM PortWidth is 24 (inconsistent "
    "firmware), aborting driver load",
    "IDROM IOPorts is 2 but llio num_ioport_connectors is 1, driver and firmware are "
    "inconsistent, aborting driver load",
    "IDROM ClockLow is 12345, that's too low, aborting driver load",
    "IDROM ClockHigh is 0, that's too low, aborting driver load",
    "pin 0 primary tag is 0 (end-of-list sentinel), expected 144 pins!",
    "hm2_set_pin_source: invalid pin number 0",
    "invalid IDROM PortWidth 24, this board has 5 pins per connector, aborting load",
    "IDROM IOPorts is 0 but llio num_ioport_connectors is 1, driver and firmware are "
    "inconsistent, aborting driver load",
};

static void test_hm2_test_patterns(void)
{
    for (int n = 0; n < HM2_TEST_NUM_PATTERNS; n++) {
        CHECK_EQ_INT(hm2_test_pattern_setup(&im, n, 0), 0);
        expect_fail(NULL, linuxcnc_pattern_msg[n]);
    }
    /* pattern 0 also prints the second cookie line */
    hm2_test_pattern_setup(&im, 0, 0);
    expect_fail(NULL, "FPGA failed to initialize, or unexpected firmware?");
    /* pattern 4: the IDROM dump follows a PortWidth error */
    hm2_test_pattern_setup(&im, 4, 0);
    expect_fail(NULL, "    Port Width: 0");
    CHECK_EQ_INT(hm2_test_pattern_setup(&im, 15, 0), -EINVAL);
    CHECK_EQ_INT(hm2_test_pattern_setup(&im, -1, 0), -EINVAL);
}

/* ---- corruptions of a valid 5i20 SVST8_4 image ---- */
#define MD(i) (T_IDROM + T_MD_OFF + 12u * (i))
#define PD(i) (T_IDROM + T_PD_OFF + 4u * (i))
/* MD table order of SVST8_4: 0 Watchdog, 1 IOPort, 2 Encoder, 3 PWMGen,
 * 4 StepGen, 5 LED (data/PIN_SVST8_4_72.modules.csv) */

static void md_set(int i, uint32_t w0, uint32_t w1, uint32_t w2)
{
    hm2_image_put32(&im, MD(i), w0);
    hm2_image_put32(&im, MD(i) + 4, w1);
    hm2_image_put32(&im, MD(i) + 8, w2);
}

static void test_corruptions(void)
{
    /* 1 PD primary tag not IOPort */
    t_setup_5i20(&im);
    hm2_image_put32(&im, PD(5), 0x04000000);
    expect_fail(NULL, "pin 5 primary tag is 4 (Encoder), not IOPort!");
    /* 2 PD table ends early (sentinel) */
    t_setup_5i20(&im);
    hm2_image_put32(&im, PD(40), 0);
    expect_fail(NULL, "pin 40 primary tag is 0 (end-of-list sentinel), expected 72 pins!");
    /* 3 MD with invalid clock tag */
    t_setup_5i20(&im);
    hm2_image_put32(&im, MD(2), 0x08030204);
    expect_fail(NULL, "Module Descriptor 2 (at 0x0458) has invalid ClockTag 3");
    /* 4 MD with invalid register stride select */
    t_setup_5i20(&im);
    hm2_image_put32(&im, MD(3) + 4, 0x02054000);
    expect_fail(NULL, "Module Descriptor 3 (at 0x0464) has invalid RegisterStride 2");
    /* 5 MD with invalid instance stride select */
    t_setup_5i20(&im);
    hm2_image_put32(&im, MD(4) + 4, 0x300A2000);
    expect_fail(NULL, "Module Descriptor 4 (at 0x0470) has invalid InstanceStride 3");
    /* 6 watchdog with 4 registers */
    t_setup_5i20(&im);
    md_set(0, 0x01010002, 0x00040C00, 0);
    expect_fail(NULL, "inconsistent Module Descriptor for Watchdog, not loading driver");
    expect_fail(NULL, "    NumRegisters = 4, expected 3");
    expect_fail(NULL, "failed to parse Module Descriptor 0");
    /* 7 stepgen version 7 */
    t_setup_5i20(&im);
    hm2_image_put32(&im, MD(4), 0x04010705);
    expect_fail(NULL, "unknown stepgen MD:");
    expect_fail(NULL, "    Version = 7");
    /* 8 PWM version 2 */
    t_setup_5i20(&im);
    hm2_image_put32(&im, MD(3), 0x08020206);
    expect_fail(NULL, "Unsupported PWM firmware version");
    /* 9 encoder multiple-register bitmap wrong */
    t_setup_5i20(&im);
    hm2_image_put32(&im, MD(2) + 8, 0x7);
    expect_fail(NULL, "inconsistent Encoder Module Descriptor!");
    /* 10 duplicate MD (a second encoder descriptor replaces the LED) */
    t_setup_5i20(&im);
    md_set(5, 0x08010204, 0x00053000, 3);
    expect_fail(NULL, "found duplicate Module Descriptor for Encoder (inconsistent firmware), "
                      "not loading driver");
    /* 11 IOPort instances differ from IDROM IOPorts */
    t_setup_5i20(&im);
    hm2_image_put32(&im, MD(1), 0x02010003);
    expect_fail(NULL, "IDROM IOPorts is 3 but MD IOPort NumInstances is 2, inconsistent "
                      "firmware, aborting driver load");
    /* 12 more encoders requested than exist */
    t_setup_5i20(&im);
    expect_fail("num_encoders=9",
                "config.num_encoders=9, but only 8 are available, not loading driver");
    expect_fail("num_stepgens=5",
                "config.num_stepgens=5, but only 4 are available, not loading driver");
    expect_fail("num_pwmgens=100",
                "config.num_pwmgens=100, but only 8 are available, not loading driver");
    /* 13 IDROM offset so high the header runs past the register space */
    t_setup_5i20(&im);
    hm2_image_put32(&im, 0x10C, 0xFFF0);
    hm2_image_put32(&im, 0xFFF0, 3);
    expect_fail(NULL, "error reading IDROM");
    /* 14 pin descriptor offset past the register space */
    t_setup_5i20(&im);
    hm2_image_put32(&im, T_IDROM + 8, 0xFFFFFF00u);
    expect_fail(NULL, "error reading Pin Descriptor 0 (at 0x100000300)");
    /* 15 pin descriptors straddle the end of the space */
    t_setup_5i20(&im);
    hm2_image_put32(&im, T_IDROM + 8, 0xFC00 - 0x10);
    for (uint32_t a = 0xFFF0; a < 0x10000; a += 4)
        hm2_image_put32(&im, a, 0x03000000);
    expect_fail(NULL, "error reading Pin Descriptor 4 (at 0x10000)");
    /* 16 module descriptor offset past the register space */
    t_setup_5i20(&im);
    hm2_image_put32(&im, T_IDROM + 4, 0x00FFFC00u);
    expect_fail(NULL, "error reading Module Descriptor 0 (at 0x1000000)");
    /* 17 MD table without terminator: fill 48 slots with LEDs... each is
     * a duplicate, but the missing terminator is found first */
    t_setup_5i20(&im);
    hm2_image_put32(&im, T_IDROM + 8, 0x400); /* move PDs out of the way */
    for (uint32_t i = 0; i < 72; i++)
        hm2_image_put32(&im, T_IDROM + 0x400 + 4 * i,
                        hm2_image_get32(&im, PD(i)));
    for (int i = 6; i < 48; i++)
        md_set(i, 0x01010080, 0x00010200, 0);
    expect_fail(NULL, "Module Descriptor table at 0x0440 has no terminator (GTag 0) within 48 "
                      "entries, inconsistent firmware, aborting driver load");
    /* 18 module registers run past the register space */
    t_setup_5i20(&im);
    md_set(2, 0x08010204, 0x0005FE00, 3); /* 0xFE00 + 4*256 + 7*4 + 3 */
    expect_fail(NULL, "Module Descriptor 2 (at 0x0458): Encoder registers reach 0x1021F, past "
                      "the 64 KiB register space (inconsistent firmware), aborting driver load");
    /* 19 absurd IOWidth (llio with very wide connectors) */
    t_setup_5i20(&im);
    im.llio.pins_per_connector = 400;
    hm2_image_put32(&im, T_IDROM + 0x24, 400);
    hm2_image_put32(&im, T_IDROM + 0x20, 1200);
    expect_fail(NULL, "IDROM IOWidth is 1200 but max is 1000, aborting driver load");
    /* 20 IOWidth with 32-bit overflow of IOPorts*PortWidth */
    t_setup_5i20(&im);
    hm2_image_put32(&im, T_IDROM + 0x1C, 0x80000003u);
    hm2_image_put32(&im, T_IDROM + 0x20, 72);
    expect_fail(NULL, "IDROM IOWidth is 72, but IDROM IOPorts is -2147483645 and IDROM "
                      "PortWidth is 24 (inconsistent firmware), aborting driver load");
    /* 21 wrong config name text */
    t_setup_5i20(&im);
    hm2_image_put32(&im, 0x108, 0x00544F4D);
    expect_fail(NULL, "invalid config name, got 'HOSTMOT?', expected 'HOSTMOT2'");
    /* 22 IDROM type 4 */
    t_setup_5i20(&im);
    hm2_image_put32(&im, T_IDROM, 4);
    expect_fail(NULL, "invalid IDROM type 4, expected 2 or 3, aborting load");
    /* 23 unknown token in the config string */
    t_setup_5i20(&im);
    expect_fail("num_encoders=1 frobnicate", "invalid token in config string: \"frobnicate\"");
    expect_fail("num_encoders=x1",
                "invalid token in config string: \"num_encoders=x1\" (not a number)");
    /* 24 no IOPort MD at all but pins */
    t_setup_5i20(&im);
    md_set(1, 0x01010080, 0x00010200, 0); /* IOPort slot becomes a 2nd LED */
    expect_fail(NULL, "found duplicate Module Descriptor for LED (inconsistent firmware), not "
                      "loading driver");
    t_setup_5i20(&im);
    md_set(1, 0x01010007, 0x00015000, 0); /* IOPort slot becomes an (ignored) SPI */
    expect_fail(NULL, "hm2_set_pin_source: invalid pin number 71");
    /* 25 watchdog descriptor in the wrong clock domain is fine, but zero
     * clock frequency for the encoder's domain is caught by the header */
    t_setup_5i20(&im);
    hm2_image_put32(&im, T_IDROM + 0x28, 999999);
    expect_fail(NULL, "IDROM ClockLow is 999999, that's too low, aborting driver load");
}

/* Descriptors the driver does not run are reported and skipped. */
static void test_ignored_mds(void)
{
    int err;
    t_setup_5i20(&im);
    md_set(5, 0x01010063, 0x00017000, 0); /* gtag 99 */
    hostmot2_t *hm2 = probe(NULL, &err);
    CHECK(hm2 != NULL);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: Firmware contains unknown function (gtag-99)", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 5: 1x (unknown-gtag-99) v0: ignored", 0) >= 0);
    hm2_free(hm2);
    t_setup_5i20(&im);
    md_set(5, 0x010100C3, 0x10065A00, 0x3C); /* SSR: known name, not run */
    hm2 = probe(NULL, &err);
    CHECK(hm2 != NULL);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 5: 1x SSR v0: ignored", 0) >= 0);
    CHECK(!tlog_contains(&lg, "unknown function"));
    hm2_free(hm2);
    t_setup_5i20(&im);
    md_set(5, 0x010100C1, 0x10065A00, 0x3C); /* SSerial: run by sserial.c */
    hm2 = probe(NULL, &err);
    CHECK(hm2 != NULL);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 5: 1x Smart Serial Interface v0: accepted, using 1",
                    0) >= 0);
    hm2_free(hm2);
}

static void test_read_errors(void)
{
    static const struct {
        int32_t lo, hi;
        const char *msg;
    } cases[] = {
        {0x100, 0x103, "error reading hm2 cookie"},
        {0x104, 0x10B, "error reading HM2 Config Name"},
        {0x10C, 0x10F, "error reading IDROM Offset"},
        {0x400, 0x403, "error reading IDROM type"},
        {0x43C, 0x43C, "error reading IDROM"},
        {0x5C0 + 4 * 17, 0x5C0 + 4 * 17, "error reading Pin Descriptor 17 (at 0x0604)"},
        {0x440 + 12 * 3 + 8, 0x440 + 12 * 3 + 8, "error reading Module Descriptor 3 (at 0x0464)"},
    };
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
        t_setup_5i20(&im);
        im.fail_lo = cases[i].lo;
        im.fail_hi = cases[i].hi;
        expect_fail(NULL, cases[i].msg);
    }
}

/* Random corruption sweep: flip bytes of a valid image; the probe must
 * always come back (success or a clean failure), ASan/UBSan watching. */
static void test_random_corruption(void)
{
    uint32_t seed = 12345;
    int ok = 0, failed = 0;
    for (int iter = 0; iter < 3000; iter++) {
        t_setup_5i20(&im);
        int flips = 1 + iter % 4;
        for (int f = 0; f < flips; f++) {
            seed = seed * 1103515245u + 12345u;
            uint32_t addr = 0x400 + (seed >> 8) % 0x400;
            if (iter % 7 == 0)
                addr = 0x100 + (seed >> 8) % 16;
            seed = seed * 1103515245u + 12345u;
            im.mem[addr] = (uint8_t)(seed >> 16);
        }
        int err = 0;
        hostmot2_t *hm2 = probe(iter % 3 ? NULL : "num_encoders=2 num_stepgens=1", &err);
        if (hm2) {
            ok++;
            CHECK(err == 0);
            hm2_print_pin_usage(hm2);
            hm2_free(hm2);
        } else {
            failed++;
            CHECK(err < 0);
            CHECK(lg.n > 0);
        }
    }
    fprintf(stderr, "random corruption: %d loaded, %d refused\n", ok, failed);
    CHECK(ok > 0);
    CHECK(failed > 0);
}

/* ---- the seed's 5i20 example ---- */
/* Lines from the seed document's 5i20 printout (hostmot2-driver-doc.txt),
 * without the timestamps. */
static const char *const seed_lines[] = {
    "hm2/hm2_5i20.0: 72 I/O Pins used: ",
    "hm2/hm2_5i20.0: IO Pin 000 (P2-01): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 001 (P2-03): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 002 (P2-05): Encoder #0, pin B (Input) ",
    "hm2/hm2_5i20.0: IO Pin 003 (P2-07): Encoder #0, pin A (Input) ",
    "hm2/hm2_5i20.0: IO Pin 004 (P2-09): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 005 (P2-11): Encoder #0, pin Index (Input) ",
    "hm2/hm2_5i20.0: IO Pin 006 (P2-13): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 007 (P2-15): PWMGen #0, pin Out0 (PWM or Up) (Output) ",
    "hm2/hm2_5i20.0: IO Pin 008 (P2-17): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 009 (P2-19): PWMGen #0, pin Out1 (Dir or Down) (Output) ",
    "hm2/hm2_5i20.0: IO Pin 010 (P2-21): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 011 (P2-23): PWMGen #0, pin Not-Enable (Output) ",
    "hm2/hm2_5i20.0: IO Pin 060 (P4-25): StepGen #2, pin Step (Output) ",
    "hm2/hm2_5i20.0: IO Pin 061 (P4-27): StepGen #2, pin Direction (Output) ",
    "hm2/hm2_5i20.0: IO Pin 062 (P4-29): StepGen #2, pin (unused) (Output) ",
    "hm2/hm2_5i20.0: IO Pin 063 (P4-31): StepGen #2, pin (unused) (Output) ",
    "hm2/hm2_5i20.0: IO Pin 064 (P4-33): StepGen #2, pin (unused) (Output) ",
    "hm2/hm2_5i20.0: IO Pin 065 (P4-35): StepGen #2, pin (unused) (Output) ",
    "hm2/hm2_5i20.0: IO Pin 066 (P4-37): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 067 (P4-39): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 068 (P4-41): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 069 (P4-43): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 070 (P4-45): IOPort ",
    "hm2/hm2_5i20.0: IO Pin 071 (P4-47): IOPort ",
};

/* Independent expectation for every pin from the CSV and the spec rules. */
static void expected_line(const struct t_csv *csv, int i, int num_enc, int num_pwm, int num_sg,
                          int width, char *out, size_t len)
{
    static const char *conn[3] = {"P2", "P3", "P4"};
    int tag = atoi(t_csv_get(csv, i, "sec_tag"));
    int unit = atoi(t_csv_get(csv, i, "sec_unit"));
    int sp = atoi(t_csv_get(csv, i, "sec_pin"));
    const char *sname = t_csv_get(csv, i, "sec_pin_name");
    char pre[64];
    snprintf(pre, sizeof(pre), "hm2/hm2_5i20.0: IO Pin %03d (%s-%02d):", i, conn[i / 24],
             2 * (i % 24) + 1);
    int used = 0;
    const char *fn = "", *pn = sname;
    if (tag == 4) {
        used = unit < num_enc;
        fn = "Encoder";
    } else if (tag == 6) {
        used = unit < num_pwm;
        fn = "PWMGen";
        if (!strcmp(sname, "Out0"))
            pn = "Out0 (PWM or Up)";
        else if (!strcmp(sname, "Out1"))
            pn = "Out1 (Dir or Down)";
        else
            pn = "Not-Enable";
    } else if (tag == 5) {
        used = unit < num_sg;
        fn = "StepGen";
        if ((sp & 0x7F) > 2) {
            static char tbl[16];
            snprintf(tbl, sizeof(tbl), "%sPin", sname); /* Table2 -> Table2Pin */
            pn = tbl;
            if (width < 0)
                pn = "(unused)";
            else if ((sp & 0x7F) > width)
                used = 0;
        }
    }
    if (!used)
        snprintf(out, len, "%s IOPort", pre);
    else
        snprintf(out, len, "%s %s #%d, pin %s (%s)", pre, fn, unit, pn,
                 (sp & 0x80) ? "Output" : "Input");
}

static void check_report(const char *config, int ne, int np, int ns, int width)
{
    int err = 0;
    t_setup_5i20(&im);
    hostmot2_t *hm2 = probe(config, &err);
    CHECK(hm2 != NULL);
    if (!hm2) {
        tlog_dump(&lg);
        return;
    }
    tlog_clear(&lg);
    hm2_print_pin_usage(hm2);
    CHECK_EQ_INT(lg.n, 73);
    struct t_csv csv;
    CHECK_EQ_INT(t_csv_read(HM2_TEST_DATA "/PIN_SVST8_4_72.csv", &csv), 72);
    for (int i = 0; i < 72; i++) {
        char want[256];
        expected_line(&csv, i, ne, np, ns, width, want, sizeof(want));
        int at = tlog_find(&lg, want, 1);
        CHECK_EQ_INT(at, i + 1);
        if (at != i + 1)
            fprintf(stderr, "  want: %s\n  got:  %s\n", want, lg.line[i + 1]);
    }
    t_csv_free(&csv);
    hm2_free(hm2);
}

static void test_seed_5i20_report(void)
{
    int err = 0;
    t_setup_5i20(&im);
    hostmot2_t *hm2 =
        probe("firmware=hm2/5i20/SVST8_4.BIT num_encoders=1 num_pwmgens=1 num_stepgens=3", &err);
    CHECK(hm2 != NULL);
    CHECK_EQ_INT(err, 0);
    if (!hm2)
        return;
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: Low Level init 0.15", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 1: 3x IOPort v0: accepted, using 3", 0) == 1);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 0: 1x Watchdog v0: accepted, using 1", 0) == 2);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 2: 8x Encoder v2: accepted, using 1", 0) == 3);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 3: 8x PWMGen v0: accepted, using 1", 0) == 4);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 4: 4x StepGen v2: accepted, using 3", 0) == 5);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: MD 5: 1x LED v0: accepted, using 1", 0) == 6);
    tlog_clear(&lg);
    hm2_print_pin_usage(hm2);
    for (size_t i = 0; i < sizeof(seed_lines) / sizeof(seed_lines[0]); i++) {
        int at = tlog_find(&lg, seed_lines[i], 1);
        CHECK(at >= 0);
        if (at < 0)
            fprintf(stderr, "  seed line missing: %s\n", seed_lines[i]);
    }
    hm2_free(hm2);
    /* every pin, several configurations */
    check_report("num_encoders=1 num_pwmgens=1 num_stepgens=3", 1, 1, 3, -1);
    check_report(NULL, 8, 8, 4, -1);
    check_report("num_encoders=0 num_pwmgens=0 num_stepgens=0", 0, 0, 0, -1);
    check_report("num_stepgens=4 stepgen_width=2", 8, 8, 4, 2);
    check_report("num_stepgens=2 stepgen_width=4 num_encoders=3", 3, 8, 2, 4);
    check_report("num_encoders=0x3 num_pwmgens=-1", 3, 8, 4, -1);
}

static void test_queued_and_debug(void)
{
    int err = 0;
    t_setup_5i20(&im);
    hm2_image_llio_set_queued(&im, 1);
    tlog_clear(&lg);
    struct hm2_options opt = {{1, 1, 1, 1}, NULL};
    hostmot2_t *hm2 = hm2_probe(&im.llio, NULL, &opt, tlog_sink, &lg, &err);
    CHECK(hm2 != NULL);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0:     Clock Low: 33333333 Hz (33333 KHz, 33 MHz)", 0) >=
          0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: Module Descriptor 4 at 0x0470:", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0:     Clock Tag: 2 (100.000 MHz)", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0: 72 HM2 Pin Descriptors:", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/hm2_5i20.0:         Secondary Pin: 0x81 (Out0 (PWM or Up), Output)",
                    0) >= 0);
    hm2_free(hm2);
}

static int fake_split(hm2_llio_t *l)
{
    (void)l;
    return 0;
}

static void test_llio_validation(void)
{
    int err = 0;
    t_setup_5i20(&im);
    im.llio.read = NULL;
    CHECK(probe(NULL, &err) == NULL);
    CHECK_EQ_INT(err, -EINVAL);
    CHECK(tlog_find(&lg, "hm2: invalid llio: llio hm2_5i20.0 lacks read or write", 0) >= 0);
    t_setup_5i20(&im);
    im.llio.pins_per_connector = 0;
    CHECK(probe(NULL, &err) == NULL);
    CHECK(tlog_contains(&lg, "pins_per_connector 0 out of range"));
    t_setup_5i20(&im);
    hm2_image_llio_set_queued(&im, 1);
    im.llio.send_queued_writes = NULL;
    CHECK(probe(NULL, &err) == NULL);
    CHECK(tlog_contains(&lg, "only some of the queued-access functions"));
    /* the split read (read-request) comes in pairs, on top of the queued access */
    t_setup_5i20(&im);
    hm2_image_llio_set_queued(&im, 1);
    im.llio.request_queued_reads = im.llio.send_queued_reads;
    CHECK(probe(NULL, &err) == NULL);
    CHECK(tlog_contains(&lg, "only one of request_queued_reads/receive_queued_reads"));
    t_setup_5i20(&im);
    hm2_image_llio_set_queued(&im, 0);
    im.llio.request_queued_reads = fake_split;
    im.llio.receive_queued_reads = fake_split;
    CHECK(probe(NULL, &err) == NULL);
    CHECK(tlog_contains(&lg, "splits queued reads but has no queued access"));
}

static void test_pin_names(void)
{
    char buf[32];
    hm2_llio_t l;
    memset(&l, 0, sizeof(l));
    hm2_board_fill_llio(hm2_board_lookup("5i25"), 0, &l);
    CHECK_EQ_STR(l.name, "hm2_5i25.0");
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 0, buf, sizeof(buf)), "P3-01");
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 1, buf, sizeof(buf)), "P3-14");
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 16, buf, sizeof(buf)), "P3-13");
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 17, buf, sizeof(buf)), "P2-01");
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 24, buf, sizeof(buf)), "P2-17");
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 20, buf, sizeof(buf)), "P2-15");
    hm2_board_fill_llio(hm2_board_lookup("5I22-1.5m"), 1, &l);
    CHECK_EQ_STR(l.name, "hm2_5i22.1");
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 95, buf, sizeof(buf)), "P5-47");
    l.pins_per_connector = 32;
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 40, buf, sizeof(buf)), "P3-41");
    static const char *const names[3] = {"TB3-01", NULL, "internal"};
    l.io_pin_names = names;
    l.num_io_pin_names = 3;
    CHECK_EQ_STR(hm2_llio_pin_name(&l, 0, buf, sizeof(buf)), "TB3-01");
    CHECK(hm2_llio_pin_name(&l, 1, buf, sizeof(buf)) == NULL);
    CHECK(hm2_board_lookup("9x99") == NULL);
    /* Mesa's firmware-directory names of the gate-size variants */
    CHECK(hm2_board_lookup("5i22-1") == hm2_board_lookup("5i22-1.0M"));
    CHECK(hm2_board_lookup("5i22-1.5") == hm2_board_lookup("5i22-1.5M"));
    CHECK(hm2_board_lookup("3x20-2") == hm2_board_lookup("3x20-2.0M"));
    CHECK_EQ_STR(hm2_board_lookup("3x20-1")->fpga_part, "3s1000fg456");
    CHECK(hm2_board_lookup("5i22-2") == NULL);
    CHECK(hm2_board_lookup("5i20-1") == NULL);
}

int main(void)
{
    RUN(test_hm2_test_patterns);
    RUN(test_corruptions);
    RUN(test_ignored_mds);
    RUN(test_read_errors);
    RUN(test_random_corruption);
    RUN(test_seed_5i20_report);
    RUN(test_queued_and_debug);
    RUN(test_llio_validation);
    RUN(test_pin_names);
    tlog_clear(&lg);
    return check_summary();
}
