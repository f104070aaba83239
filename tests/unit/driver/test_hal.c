/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * The HAL layer of the hostmot2 core against a test-double HAL and a
 * 5i20/SVST8_4 register image: exported names (seed + 2.9), the registers
 * written at load and per period (expected values computed by hand from
 * spec §9/§10), watchdog bite and recovery, I/O errors, unregister, and
 * registration failing at every HAL export without leaks.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../check.h"
#include "../../../host/driver/hostmot2/hm2_hal.h"
#include "fake_hal.h"
#include "hm2/boards.h"
#include "test_patterns.h"
#include "testlib.h"

static struct hm2_image_llio im;
static struct tlog lg;
#define PFX "hm2_5i20.0"
#define PERIOD 1000000L

/* write log: every register write in order */
static uint32_t wlog_addr[65536], wlog_val[65536];
static int wlog_n;
static void on_write(struct hm2_image_llio *i, uint32_t addr, uint32_t v)
{
    (void)i;
    if (wlog_n < 65536) {
        wlog_addr[wlog_n] = addr;
        wlog_val[wlog_n] = v;
        wlog_n++;
    }
}
static int wlog_count(uint32_t addr)
{
    int n = 0;
    for (int i = 0; i < wlog_n; i++)
        n += wlog_addr[i] == addr;
    return n;
}

static int do_register(const char *config)
{
    struct hm2_hal_options o = {{{0, 0, 0, 0}, NULL}, tlog_sink, &lg};
    tlog_clear(&lg);
    im.llio.comp_id = 7;
    return hm2_register_opts(&im.llio, config, &o);
}

static void setup(const char *config)
{
    fake_hal_reset();
    t_setup_5i20(&im);
    im.on_write = on_write;
    wlog_n = 0;
    int r = do_register(config);
    CHECK_EQ_INT(r, 0);
    if (r)
        tlog_dump(&lg);
}

static uint32_t reg(uint32_t addr)
{
    return hm2_image_get32(&im, addr);
}

static void test_names(void)
{
    setup("firmware=hm2/5i20/SVST8_4.BIT num_encoders=1 num_pwmgens=1 num_stepgens=3");
    /* functions: seed + 2.9 */
    const char *f[] = {PFX ".read", PFX ".write", PFX ".pet_watchdog", PFX ".pet-watchdog",
                       PFX ".read_gpio", PFX ".write_gpio"};
    for (size_t i = 0; i < 6; i++)
        CHECK(fake_hal_find(f[i]) && fake_hal_find(f[i])->kind == FAKE_FUNCT);
    CHECK_EQ_INT(fake_hal_count(PFX, FAKE_FUNCT), 6);
    CHECK(fake_hal_find(PFX ".io_error") != NULL);
    CHECK(fake_hal_find(PFX ".watchdog.has_bit")->kind == FAKE_PIN);
    CHECK_EQ_INT(fake_hal_find(PFX ".watchdog.has_bit")->dir, HAL_IO);
    CHECK_EQ_INT(*fake_u32(PFX ".watchdog.timeout_ns"), 1000000000);
    /* GPIO: 72 pins all with in/in_not; full GPIO have out/is_output */
    CHECK_EQ_INT(fake_hal_count(PFX ".gpio.", -1) > 0, 1);
    CHECK(fake_hal_find(PFX ".gpio.000.out") != NULL);
    CHECK(fake_hal_find(PFX ".gpio.000.is_output") != NULL);
    CHECK(fake_hal_find(PFX ".gpio.002.in") != NULL);
    CHECK(fake_hal_find(PFX ".gpio.002.out") == NULL);
    CHECK(fake_hal_find(PFX ".gpio.002.invert_output") == NULL);
    CHECK(fake_hal_find(PFX ".gpio.007.invert_output") != NULL);
    CHECK(fake_hal_find(PFX ".gpio.007.is_output") == NULL);
    CHECK(fake_hal_find(PFX ".gpio.071.out") != NULL);
    int full = 0, mod_out = 0;
    for (int i = 0; i < 72; i++) {
        char n[64];
        snprintf(n, sizeof(n), PFX ".gpio.%03d.in_not", i);
        CHECK(fake_hal_find(n) != NULL);
        snprintf(n, sizeof(n), PFX ".gpio.%03d.out", i);
        full += fake_hal_find(n) != NULL;
        snprintf(n, sizeof(n), PFX ".gpio.%03d.is_opendrain", i);
        mod_out += fake_hal_find(n) != NULL;
    }
    /* 1 encoder (3 pins), 1 pwm (3 outputs), 3 stepgens (6 outputs each) */
    CHECK_EQ_INT(full, 72 - 3 - 3 - 18);
    CHECK_EQ_INT(mod_out, full + 3 + 18);
    /* aliases */
    const struct fake_obj *a = fake_hal_find(PFX ".pwmgen.00.out0.invert_output");
    CHECK(a && a->kind == FAKE_ALIAS && strcmp(a->target, PFX ".gpio.007.invert_output") == 0);
    a = fake_hal_find(PFX ".stepgen.02.step.is_opendrain");
    CHECK(a && strcmp(a->target, PFX ".gpio.060.is_opendrain") == 0);
    CHECK(fake_hal_find(PFX ".stepgen.02.table2.invert_output") != NULL);
    CHECK(fake_hal_find(PFX ".pwmgen.00.enable.invert_output") != NULL);
    /* module instances */
    CHECK(fake_hal_find(PFX ".encoder.00.velocity") != NULL);
    CHECK(fake_hal_find(PFX ".encoder.01.velocity") == NULL);
    CHECK_EQ_INT(fake_hal_find(PFX ".encoder.00.index-enable")->dir, HAL_IO);
    CHECK(fake_hal_find(PFX ".encoder.00.probe-enable") == NULL); /* v2 has no probe */
    CHECK_EQ_INT(*fake_u32(PFX ".encoder.sample-frequency"), 33333333); /* 25 MHz -> /1 */
    CHECK(fake_hal_find(PFX ".stepgen.02.position-cmd") != NULL);
    CHECK(fake_hal_find(PFX ".stepgen.03.position-cmd") == NULL);
    CHECK(fake_hal_find(PFX ".stepgen.00.swap_step_dir") == NULL);
    CHECK(fake_hal_find(PFX ".stepgen.00.table-data-3") != NULL);
    CHECK_EQ_INT(*fake_u32(PFX ".stepgen.00.steplen"), 491490);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.maxaccel"), 1.0, 0);
    CHECK(fake_hal_find(PFX ".pwmgen.00.dither") == NULL); /* v0 */
    CHECK(fake_hal_find(PFX ".pwmgen.01.value") == NULL);
    CHECK_EQ_INT(*fake_u32(PFX ".pwmgen.pwm_frequency"), 20000);
    CHECK_EQ_INT(*fake_u32(PFX ".pwmgen.pdm_frequency"), 20000);
    CHECK(fake_hal_find(PFX ".led.CR08") != NULL);
    CHECK(fake_hal_find(PFX ".led.CR09") == NULL);
    CHECK(fake_hal_find(PFX ".raw.read_address") == NULL);
    CHECK(tlog_find(&lg, "hm2/" PFX ": registered", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/" PFX ":     IO Pin 062 (P4-29): StepGen #2, pin (unused) (Output)",
                    0) >= 0);
    hm2_unregister_board(&im.llio);
    CHECK(im.llio.hm2 == NULL);
    CHECK_EQ_INT(reg(0x0C00), 0); /* unload makes the watchdog bite */
    CHECK(tlog_find(&lg, "hm2/" PFX ": unregistered", 0) >= 0);
}

/* An EPP-style board (not threadsafe) has no read_gpio/write_gpio. */
static void test_not_threadsafe(void)
{
    fake_hal_reset();
    hm2_image_llio_init(&im, "hm2_7i43.0");
    hm2_image_llio_set_board(&im, hm2_board_lookup("7i43"), 0);
    struct t_firmware fw = {HM2_TEST_DATA "/PIN_SV8_48.csv", HM2_TEST_DATA "/PIN_SV8_48.modules.csv",
                            "MESA7I43", 50000000, 100000000, 24, 2};
    CHECK_EQ_INT(t_build_image(&im, &fw), 48);
    CHECK_EQ_INT(do_register("num_encoders=2"), 0);
    CHECK(fake_hal_find("hm2_7i43.0.read") != NULL);
    CHECK(fake_hal_find("hm2_7i43.0.read_gpio") == NULL);
    CHECK(fake_hal_find("hm2_7i43.0.write_gpio") == NULL);
    CHECK_EQ_INT(fake_hal_count("hm2_7i43.0", FAKE_FUNCT), 4);
    /* 50 MHz: TSDiv = 25 - 2, QFilterRate for 25 MHz = 50/25 - 2 = 0 */
    CHECK_EQ_INT(reg(0x3200), 23);
    CHECK_EQ_INT(reg(0x3400), 0);
    CHECK_EQ_INT(*fake_u32("hm2_7i43.0.encoder.sample-frequency"), 25000000);
    hm2_unregister_board(&im.llio);
}

static void test_load_registers(void)
{
    setup("num_encoders=2 num_pwmgens=2 num_stepgens=2");
    CHECK_EQ_INT(reg(0x0C00), 0x80000000u); /* watchdog disabled until first write */
    CHECK_EQ_INT(reg(0x2900), 0xFFFFFFFFu); /* stepgen master DDS */
    /* 491490 ns * 33333333 Hz / 1e9 = 16382.99... -> 16382 */
    CHECK_EQ_INT(reg(0x2300), 16382);
    CHECK_EQ_INT(reg(0x2504), 16382);
    CHECK_EQ_INT(reg(0x2200), 0); /* step/dir */
    CHECK_EQ_INT(reg(0x3200), 33333333 / 2000000 - 2);
    CHECK_EQ_INT(reg(0x3400), 0xFFF);
    CHECK_EQ_INT(reg(0x3100), 1u << 11); /* filter on */
    /* PWM: 20 kHz at 100 MHz: 20000*65536*4096/1e8 = 53687.09 -> 12 bits */
    CHECK_EQ_INT(reg(0x4200), 53687);
    CHECK_EQ_INT(reg(0x4300), 13);  /* 20000*65536/1e8 = 13.1 */
    CHECK_EQ_INT(reg(0x4100), 0x23); /* 12 bits, PWM/dir, double buffered */
    CHECK_EQ_INT(reg(0x4400), 0);
    /* IOPort: AltSource for every allocated pin, DDR for none yet */
    uint32_t alt0 = 0;
    struct t_csv csv;
    t_csv_read(HM2_TEST_DATA "/PIN_SVST8_4_72.csv", &csv);
    uint32_t alt[3] = {0, 0, 0}, ddr[3] = {0, 0, 0};
    for (int i = 0; i < 72; i++) {
        int tag = atoi(t_csv_get(&csv, i, "sec_tag"));
        int unit = atoi(t_csv_get(&csv, i, "sec_unit"));
        int sp = atoi(t_csv_get(&csv, i, "sec_pin"));
        if ((tag == 4 || tag == 6 || tag == 5) && unit < 2) {
            alt[i / 24] |= 1u << (i % 24);
            if (sp & 0x80)
                ddr[i / 24] |= 1u << (i % 24);
        }
    }
    t_csv_free(&csv);
    (void)alt0;
    for (int p = 0; p < 3; p++) {
        CHECK_EQ_INT(reg(0x1200 + 4u * (uint32_t)p), alt[p]);
        CHECK_EQ_INT(reg(0x1100 + 4u * (uint32_t)p), 0);
    }
    /* first write: module outputs become outputs, watchdog armed + petted */
    fake_run(PFX ".write", PERIOD);
    for (int p = 0; p < 3; p++)
        CHECK_EQ_INT(reg(0x1100 + 4u * (uint32_t)p), ddr[p]);
    CHECK_EQ_INT(reg(0x0E00), 0x5A000000u);
    CHECK_EQ_INT(reg(0x0C00), 33333332); /* 1e9 ns * 33.333333 MHz - 1 */
    /* change timeout */
    *fake_u32(PFX ".watchdog.timeout_ns") = 5000000;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x0C00), 166665); /* 5e6*0.033333333 - 1 = 165665.665 -> 166665 */
    *fake_u32(PFX ".watchdog.timeout_ns") = 4000000000u; /* fits at 33 MHz */
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x0C00), 133333331); /* 4e9 * 0.033333333 - 1 */
    /* too short for the period */
    *fake_u32(PFX ".watchdog.timeout_ns") = 1000000;
    fake_run(PFX ".write", PERIOD);
    CHECK(tlog_contains(&lg, "dangerously short"));
    hm2_unregister_board(&im.llio);
}

static void test_gpio(void)
{
    setup(NULL); /* everything enabled: gpio 66..71? all used by stepgen 3 */
    hm2_unregister_board(&im.llio);
    setup("num_encoders=0 num_pwmgens=0 num_stepgens=0");
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x1100), 0);
    *fake_bit(PFX ".gpio.000.is_output") = 1;
    *fake_bit(PFX ".gpio.000.out") = 1;
    *fake_bit(PFX ".gpio.025.is_output") = 1;
    *fake_bit(PFX ".gpio.025.invert_output") = 1;
    *fake_bit(PFX ".gpio.026.is_output") = 1;
    *fake_bit(PFX ".gpio.026.is_opendrain") = 1;
    *fake_bit(PFX ".gpio.027.invert_output") = 1; /* input: no effect */
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x1100), 1);
    CHECK_EQ_INT(reg(0x1000), 1);
    CHECK_EQ_INT(reg(0x1104), 0x6);
    CHECK_EQ_INT(reg(0x1404), 0x2);
    CHECK_EQ_INT(reg(0x1304), 0x4);
    CHECK_EQ_INT(reg(0x1200), 0);
    /* inputs */
    hm2_image_put32(&im, 0x1008, 0x00800001);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".gpio.048.in"), 1);
    CHECK_EQ_INT(*fake_bit(PFX ".gpio.048.in_not"), 0);
    CHECK_EQ_INT(*fake_bit(PFX ".gpio.071.in"), 1);
    CHECK_EQ_INT(*fake_bit(PFX ".gpio.049.in"), 0);
    CHECK_EQ_INT(*fake_bit(PFX ".gpio.049.in_not"), 1);
    /* read_gpio / write_gpio alone */
    hm2_image_put32(&im, 0x1008, 0x2);
    fake_run(PFX ".read_gpio", 50000);
    CHECK_EQ_INT(*fake_bit(PFX ".gpio.049.in"), 1);
    *fake_bit(PFX ".gpio.000.out") = 0;
    fake_run(PFX ".write_gpio", 50000);
    CHECK_EQ_INT(reg(0x1000), 0);
    /* config registers are written only when they change */
    int before = wlog_count(0x1100);
    fake_run(PFX ".write", PERIOD);
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(wlog_count(0x1100), before);
    hm2_unregister_board(&im.llio);
}

static void test_watchdog_bite(void)
{
    setup("num_encoders=1");
    fake_run(PFX ".read", PERIOD);
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".watchdog.has_bit"), 0);
    hm2_image_put32(&im, 0x0D00, 1); /* the dog bites */
    hm2_image_put32(&im, 0x1100, 0); /* ... and clears DDR */
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".watchdog.has_bit"), 1);
    CHECK(tlog_find(&lg, "hm2/" PFX ": Watchdog has bit! (set the .has-bit pin to False to resume)",
                    0) >= 0);
    /* LinuxCNC 2.9: the transfers go on while bitten (pet, rates, GPIO
     * data), but no configuration is rewritten until has_bit is cleared */
    hm2_image_put32(&im, 0x0E00, 0);
    int writes = (int)im.writes;
    fake_run(PFX ".write", PERIOD);
    CHECK((int)im.writes > writes);
    CHECK_EQ_INT(reg(0x0E00), 0x5A000000u); /* still petted */
    hm2_image_put32(&im, 0x0E00, 0);
    fake_run(PFX ".pet_watchdog", PERIOD);
    CHECK_EQ_INT(reg(0x0E00), 0x5A000000u);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(reg(0x1100), 0);   /* DDR not restored behind the user's back */
    CHECK_EQ_INT(reg(0x0D00), 1);   /* bite not cleared */
    CHECK_EQ_INT(*fake_bit(PFX ".watchdog.has_bit"), 1);
    CHECK(tlog_find(&lg, "hm2/" PFX ": trying to recover from IO error or Watchdog bite", 0) < 0);
    CHECK_EQ_INT(*fake_bit(PFX ".io_error"), 0);
    *fake_bit(PFX ".watchdog.has_bit") = 0;
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".watchdog.has_bit"), 0);
    fake_run(PFX ".write", PERIOD);
    CHECK(tlog_find(&lg, "hm2/" PFX ": trying to recover from IO error or Watchdog bite", 0) >= 0);
    CHECK(tlog_find(&lg, "hm2/" PFX ": error recover successful!", 0) >= 0);
    CHECK_EQ_INT(reg(0x0D00), 0);
    CHECK(reg(0x1100) != 0); /* DDR restored */
    CHECK_EQ_INT(reg(0x0C00), 33333332);
    /* pet_watchdog alone pets */
    hm2_image_put32(&im, 0x0E00, 0);
    fake_run(PFX ".pet_watchdog", PERIOD);
    CHECK_EQ_INT(reg(0x0E00), 0x5A000000u);
    hm2_unregister_board(&im.llio);
}

static void io_error_case(int queued)
{
    setup(NULL);
    hm2_image_llio_set_queued(&im, queued);
    fake_run(PFX ".read", PERIOD);
    im.fail_lo = 0x3000;
    im.fail_hi = 0x3003;
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".io_error"), 1);
    unsigned reads = im.reads, writes = im.writes;
    fake_run(PFX ".read", PERIOD);
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(im.reads, reads);
    CHECK_EQ_INT(im.writes, writes);
    im.fail_lo = im.fail_hi = -1;
    *fake_bit(PFX ".io_error") = 0;
    fake_run(PFX ".write", PERIOD);
    CHECK(tlog_find(&lg, "hm2/" PFX ": error recover successful!", 0) >= 0);
    CHECK(im.writes > writes);
    CHECK_EQ_INT(im.nrq, 0);
    CHECK_EQ_INT(im.nwq, 0);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".io_error"), 0);
    hm2_unregister_board(&im.llio);
}

static void test_io_error(void)
{
    io_error_case(0);
    io_error_case(1);
}

static void enc_set(int inst, uint16_t count, uint16_t ts)
{
    hm2_image_put32(&im, 0x3000 + 4u * (uint32_t)inst, (uint32_t)ts << 16 | count);
}

static void test_encoder(void)
{
    hm2_image_put32(&im, 0x3000, 0); /* (setup rebuilds the image) */
    setup("num_encoders=2");
    /* counts start at 0 whatever the counter held: preset before the
     * first read happened inside register, so start from there */
    enc_set(0, 1000, 100);
    hm2_image_put32(&im, 0x3300, 100);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_s32(PFX ".encoder.00.rawcounts"), 1000);
    *fake_float(PFX ".encoder.00.scale") = 4.0;
    /* forward past 65535 in steps below half the counter range */
    enc_set(0, 30000, 150);
    fake_run(PFX ".read", PERIOD);
    enc_set(0, 60000, 200);
    fake_run(PFX ".read", PERIOD);
    enc_set(0, 65530, 300);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_s32(PFX ".encoder.00.rawcounts"), 65530);
    enc_set(0, 10, 400);
    hm2_image_put32(&im, 0x3300, 400);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_s32(PFX ".encoder.00.count"), 65546);
    CHECK_NEAR(*fake_float(PFX ".encoder.00.position"), 65546 / 4.0, 1e-9);
    /* 16 counts in 100 ticks of (14+2)/33333333 s: 16/4 / (100*16/33333333) */
    double v = (16.0 / 4.0) / (100.0 * 16.0 / 33333333.0);
    CHECK_NEAR(*fake_float(PFX ".encoder.00.velocity"), v, 1e-6 * v);
    CHECK_NEAR(*fake_float(PFX ".encoder.00.velocity-rpm"), 60 * v, 1e-6 * v * 60);
    /* reset */
    *fake_bit(PFX ".encoder.00.reset") = 1;
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_s32(PFX ".encoder.00.count"), 0);
    CHECK_EQ_INT(*fake_s32(PFX ".encoder.00.rawcounts"), 65546);
    *fake_bit(PFX ".encoder.00.reset") = 0;
    /* index: enable -> control register gets LatchOnIndex|JustOnce|filter */
    *fake_bit(PFX ".encoder.00.index-enable") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3100), (1u << 4) | (1u << 6) | (1u << 11));
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.00.index-enable"), 1); /* no event yet */
    /* event: hardware cleared bit 4 and latched count 20 */
    hm2_image_put32(&im, 0x3100, (20u << 16) | (1u << 6) | (1u << 11));
    enc_set(0, 25, 500);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.00.index-enable"), 0);
    CHECK_EQ_INT(*fake_s32(PFX ".encoder.00.count"), 5); /* 25 - 20 */
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3100) & 0xFFFF, 1u << 11);
    /* parameters into the control word */
    *fake_bit(PFX ".encoder.01.counter-mode") = 1;
    *fake_bit(PFX ".encoder.01.index-invert") = 1;
    *fake_bit(PFX ".encoder.01.index-mask") = 1;
    *fake_bit(PFX ".encoder.01.index-mask-invert") = 1;
    *fake_bit(PFX ".encoder.01.filter") = 0;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3104), (1u << 10) | (1u << 3) | (1u << 9) | (1u << 8));
    /* quad error: W1C pulse on enable, message once */
    *fake_bit(PFX ".encoder.01.quad-error-enable") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK(wlog_val[wlog_n - 1] & 0x8000u);
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3104) & 0x8000u, 0);
    hm2_image_put32(&im, 0x3104, 0x8000u | 0x3);
    fake_run(PFX ".read", PERIOD);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.01.quad-error"), 1);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.01.input-a"), 1);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.01.input-b"), 1);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.01.input-index"), 0);
    int msgs = 0;
    for (int i = 0; i < lg.n; i++)
        msgs += strcmp(lg.line[i], "hm2/" PFX ": Encoder 1: quadrature count error") == 0;
    CHECK_EQ_INT(msgs, 1);
    /* an error latched while reporting was off is stale: not reported on the
     * read before the write that clears it when quad-error-enable rises */
    *fake_bit(PFX ".encoder.01.quad-error-enable") = 0;
    fake_run(PFX ".write", PERIOD);
    hm2_image_put32(&im, 0x3104, 0x8000u);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.01.quad-error"), 0);
    *fake_bit(PFX ".encoder.01.quad-error-enable") = 1;
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.01.quad-error"), 0);
    fake_run(PFX ".write", PERIOD);
    CHECK(reg(0x3104) & 0x8000u); /* the clear (write 1) went out */
    for (int i = msgs = 0; i < lg.n; i++)
        msgs += strcmp(lg.line[i], "hm2/" PFX ": Encoder 1: quadrature count error") == 0;
    CHECK_EQ_INT(msgs, 1);
    /* sample frequency and hires timestamp */
    *fake_u32(PFX ".encoder.sample-frequency") = 1000000;
    *fake_bit(PFX ".encoder.hires-timestamp") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3400), 33 - 2);
    CHECK_EQ_INT(*fake_u32(PFX ".encoder.sample-frequency"), 33333333 / 33);
    CHECK_EQ_INT(reg(0x3200), 3 - 2);
    hm2_unregister_board(&im.llio);
}

/* QCount version 0x83 (probe-capable): probe-enable/probe-invert exist, go
 * into CCR bits 13/12 with JustOnce, and a CCR read with bit 13 cleared is
 * the latch: count-latched and position-latched, probe-enable back to 0 */
static void test_encoder_probe(void)
{
    fake_hal_reset();
    t_setup_5i20(&im);
    im.on_write = on_write;
    wlog_n = 0;
    for (uint32_t a = 0x440; a < 0x5C0; a += 12) {
        uint32_t w0 = reg(a);
        if ((w0 & 0xFFu) == 4u)
            hm2_image_put32(&im, a, (w0 & ~0xFF00u) | 0x8300u);
    }
    CHECK_EQ_INT(do_register("num_encoders=1"), 0);
    CHECK(fake_hal_find(PFX ".encoder.00.probe-enable") != NULL);
    CHECK(fake_hal_find(PFX ".encoder.00.probe-invert") != NULL);
    enc_set(0, 0, 0);
    hm2_image_put32(&im, 0x3100, 0);
    fake_run(PFX ".read", PERIOD);
    *fake_float(PFX ".encoder.00.scale") = 10.0;
    *fake_bit(PFX ".encoder.00.probe-enable") = 1;
    *fake_bit(PFX ".encoder.00.probe-invert") = 1;
    fake_run(PFX ".write", PERIOD);
    uint32_t armed = (1u << 13) | (1u << 12) | (1u << 11) | (1u << 6);
    CHECK_EQ_INT(reg(0x3100), armed);
    enc_set(0, 12, 50);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.00.probe-enable"), 1); /* bit 13 still set */
    hm2_image_put32(&im, 0x3100, (30u << 16) | (armed & ~(1u << 13)));
    enc_set(0, 40, 90);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_bit(PFX ".encoder.00.probe-enable"), 0);
    CHECK_EQ_INT(*fake_s32(PFX ".encoder.00.count-latched"), 30);
    CHECK_NEAR(*fake_float(PFX ".encoder.00.position-latched"), 3.0, 1e-12);
    CHECK_EQ_INT(*fake_s32(PFX ".encoder.00.count"), 40);
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3100) & 0xFFFFu, (1u << 12) | (1u << 11));
    hm2_unregister_board(&im.llio);
}

static void test_stepgen(void)
{
    setup("num_stepgens=2");
    /* velocity mode, no accel limit */
    *fake_float(PFX ".stepgen.00.position-scale") = 200.0;
    *fake_float(PFX ".stepgen.00.maxaccel") = 0.0;
    *fake_u32(PFX ".stepgen.00.steplen") = 1000;
    *fake_u32(PFX ".stepgen.00.stepspace") = 1000;
    *fake_bit(PFX ".stepgen.00.control-type") = 1;
    *fake_float(PFX ".stepgen.00.velocity-cmd") = 10.0;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x2000), 0); /* not enabled */
    *fake_bit(PFX ".stepgen.00.enable") = 1;
    fake_run(PFX ".write", PERIOD);
    /* 10 units/s * 200 steps/unit = 2000 steps/s; * 2^32 / 33333333 */
    uint32_t want = (uint32_t)(int32_t)(2000.0 * 4294967296.0 / 33333333.0);
    CHECK_EQ_INT(reg(0x2000), want);
    CHECK_EQ_INT(*fake_s32(PFX ".stepgen.00.dbg_step_rate"), (int32_t)want);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.velocity-fb"), 10.0, 1e-12);
    *fake_float(PFX ".stepgen.00.velocity-cmd") = -10.0;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT((int32_t)reg(0x2000), -(int32_t)want);
    /* maxvel: physical limit from steplen+stepspace = 1e9/(983 us) / 200 */
    *fake_float(PFX ".stepgen.00.maxvel") = 5000.0;
    fake_run(PFX ".write", PERIOD);
    double phys = 1e9 / (1000.0 + 1000.0) / 200.0;
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.maxvel"), phys, 1e-9);
    CHECK(tlog_contains(&lg, "stepgen.00.maxvel is too big"));
    *fake_float(PFX ".stepgen.00.maxvel") = -2.0;
    fake_run(PFX ".write", PERIOD);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.maxvel"), 2.0, 0);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.velocity-fb"), -2.0, 1e-12);
    /* feedback from the 16.16 accumulator, including a wrap */
    hm2_image_put32(&im, 0x2100, 5u << 16);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_s32(PFX ".stepgen.00.counts"), 5);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.position-fb"), 5.0 / 200.0, 1e-12);
    hm2_image_put32(&im, 0x2100, 0xFFFF8000u);
    fake_run(PFX ".read", PERIOD);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.position-fb"), -0.5 / 200.0, 1e-12);
    hm2_image_put32(&im, 0x2100, 0x00018000u);
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_s32(PFX ".stepgen.00.counts"), 1);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.position-fb"), 1.5 / 200.0, 1e-12);
    *fake_bit(PFX ".stepgen.00.position-reset") = 1;
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_s32(PFX ".stepgen.00.counts"), 0);
    /* timing parameters -> registers, clipping */
    *fake_u32(PFX ".stepgen.01.steplen") = 3000;
    *fake_u32(PFX ".stepgen.01.dirsetup") = 1000000;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x2504), 99); /* 3000 ns * 33.333333 MHz = 99.99 -> 99 */
    CHECK_EQ_INT(reg(0x2304), 0x3FFF);
    CHECK_EQ_INT(*fake_u32(PFX ".stepgen.01.dirsetup"), 491490); /* 16383 clocks in ns */
    CHECK(tlog_contains(&lg, "stepgen.01.dirsetup 1000000 ns is longer than the firmware"));
    /* step types and table mode */
    *fake_u32(PFX ".stepgen.01.step_type") = 2;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x2204), 2);
    int mark = wlog_n;
    *fake_u32(PFX ".stepgen.01.step_type") = 4;
    *fake_u32(PFX ".stepgen.01.table-data-0") = 0x0C060309;
    fake_run(PFX ".write", PERIOD);
    uint32_t want_tbl[4] = {0x0C, 0x06, 0x03, 0x09};
    int k = 0;
    for (int i = mark; i < wlog_n; i++)
        if (wlog_addr[i] == 0x2704 && k < 4)
            CHECK_EQ_INT(wlog_val[i], want_tbl[k++]);
    CHECK_EQ_INT(k, 4);
    CHECK_EQ_INT(reg(0x2804), 3);
    CHECK_EQ_INT(reg(0x2204), 3);
    *fake_u32(PFX ".stepgen.01.step_type") = 17;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x2204), 0);
    CHECK_EQ_INT(*fake_u32(PFX ".stepgen.01.step_type"), 0);
    hm2_unregister_board(&im.llio);
}

static void test_pwmgen(void)
{
    setup("num_pwmgens=3");
    *fake_float(PFX ".pwmgen.00.value") = 0.5;
    *fake_bit(PFX ".pwmgen.00.enable") = 1;
    *fake_float(PFX ".pwmgen.01.value") = -2.0; /* clipped to -1 */
    *fake_float(PFX ".pwmgen.01.scale") = 1.0;
    *fake_bit(PFX ".pwmgen.01.enable") = 1;
    *fake_float(PFX ".pwmgen.02.value") = 1.0; /* disabled -> 0 */
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x4000), (uint32_t)(0.5 * 4095 * 65536)); /* 12 bits */
    CHECK_EQ_INT(reg(0x4004), 0x80000000u | (4095u << 16));
    CHECK_EQ_INT(reg(0x4008), 0);
    CHECK_EQ_INT(reg(0x4400), 0x3);
    /* output types, frequency change */
    *fake_s32(PFX ".pwmgen.01.output-type") = 3;
    *fake_s32(PFX ".pwmgen.02.output-type") = 9;
    *fake_u32(PFX ".pwmgen.pwm_frequency") = 50000; /* 11 bits: 50000*65536*2048/1e8=67108 no; 10 */
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x4104), 0x18 | 1);  /* PDM mode, no double buffer, 10 bits -> 1 */
    CHECK_EQ_INT(reg(0x4108), 0x21);      /* forced to type 1 */
    CHECK_EQ_INT(*fake_s32(PFX ".pwmgen.02.output-type"), 1);
    CHECK_EQ_INT(reg(0x4200), 33554);     /* floor(50000*65536*1024/1e8) */
    CHECK(tlog_contains(&lg, "pwmgen.02.output-type 9 is invalid"));
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x4004), 0x80000000u | (4095u << 16)); /* PDM: 12 bits */
    CHECK_EQ_INT(reg(0x4000), (uint32_t)(0.5 * 1023 * 65536));
    *fake_u32(PFX ".pwmgen.pwm_frequency") = 1000000;
    *fake_u32(PFX ".pwmgen.pdm_frequency") = 0;
    fake_run(PFX ".write", PERIOD);
    CHECK(tlog_contains(&lg, "max PWM frequency is 195309 Hz"));
    CHECK_EQ_INT(reg(0x4200), 65535);
    CHECK_EQ_INT(reg(0x4300), 1);
    hm2_unregister_board(&im.llio);
}

static void test_led_raw_queued(void)
{
    fake_hal_reset();
    t_setup_5i20(&im);
    hm2_image_llio_set_queued(&im, 1);
    CHECK_EQ_INT(do_register("enable_raw num_leds=2"), 0);
    CHECK(fake_hal_find(PFX ".led.CR02") != NULL);
    CHECK(fake_hal_find(PFX ".led.CR03") == NULL);
    *fake_bit(PFX ".led.CR01") = 1;
    *fake_bit(PFX ".led.CR02") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x200), 0xC0000000u);
    *fake_u32(PFX ".raw.read_address") = 0x100;
    unsigned flushes = im.flushes;
    fake_run(PFX ".read", PERIOD);
    CHECK_EQ_INT(*fake_u32(PFX ".raw.read_data"), 0x55AACAFE);
    CHECK_EQ_INT(im.flushes, flushes + 1); /* one flush per read() */
    *fake_u32(PFX ".raw.write_address") = 0x7000;
    *fake_u32(PFX ".raw.write_data") = 0x1234;
    *fake_bit(PFX ".raw.write_strobe") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x7000), 0x1234);
    hm2_unregister_board(&im.llio);
    /* num_leds larger than the board: clamped */
    fake_hal_reset();
    t_setup_5i20(&im);
    CHECK_EQ_INT(do_register("num_leds=12"), 0);
    CHECK(tlog_contains(&lg, "There are only 8 LEDs on this board type, defaulting to 8"));
    hm2_unregister_board(&im.llio);
}

static void test_failures(void)
{
    /* corrupt IDROM: nothing exported */
    fake_hal_reset();
    t_setup_5i20(&im);
    hm2_image_put32(&im, 0x100, 0);
    CHECK(do_register(NULL) < 0);
    CHECK_EQ_INT(fake_hal_objects(), 0);
    CHECK(im.llio.hm2 == NULL);
    fake_hal_reset();
    hm2_test_pattern_setup(&im, 11, 0);
    CHECK(do_register(NULL) < 0);
    CHECK_EQ_INT(fake_hal_objects(), 0);
    /* a HAL export failing at any point: clean failure, no leak */
    fake_hal_reset();
    t_setup_5i20(&im);
    CHECK_EQ_INT(do_register(NULL), 0);
    int total = fake_hal_objects();
    hm2_unregister_board(&im.llio);
    CHECK(total > 500);
    for (int n = 0; n < total; n += (n < 40 ? 1 : 37)) {
        fake_hal_reset();
        t_setup_5i20(&im);
        fake_hal_fail_at(n);
        int r = do_register(NULL);
        CHECK(r < 0);
        CHECK(im.llio.hm2 == NULL);
        CHECK(tlog_contains(&lg, "exporting"));
    }
    /* comm error during the first transfer */
    fake_hal_reset();
    t_setup_5i20(&im);
    im.fail_lo = 0x2100;
    im.fail_hi = 0x2100;
    CHECK(do_register(NULL) < 0);
    CHECK(tlog_find(&lg, "hm2/" PFX ": comm errors while initializing firmware!", 0) >= 0);
    /* double registration */
    fake_hal_reset();
    t_setup_5i20(&im);
    CHECK_EQ_INT(do_register(NULL), 0);
    CHECK_EQ_INT(do_register(NULL), -EEXIST);
    hm2_unregister_board(&im.llio);
    hm2_unregister_board(&im.llio); /* second unregister is a no-op */
    fake_hal_reset();
}

/* Random corruption through the whole HAL path: whatever the probe
 * accepts must export, run and unregister cleanly (ASan/UBSan watching). */
static void test_random_corruption_full(void)
{
    uint32_t seed = 777;
    int loaded = 0;
    for (int iter = 0; iter < 400; iter++) {
        fake_hal_reset();
        t_setup_5i20(&im);
        for (int f = 0; f < 2; f++) {
            seed = seed * 1103515245u + 12345u;
            uint32_t addr = 0x400 + (seed >> 8) % 0x400;
            seed = seed * 1103515245u + 12345u;
            im.mem[addr] = (uint8_t)(seed >> 16);
        }
        if (do_register(iter % 2 ? NULL : "num_encoders=2 enable_raw") == 0) {
            loaded++;
            for (int k = 0; k < 3; k++) {
                fake_run(PFX ".read", PERIOD);
                fake_run(PFX ".write", PERIOD);
            }
            hm2_unregister_board(&im.llio);
        } else {
            CHECK(im.llio.hm2 == NULL);
        }
    }
    fprintf(stderr, "full-path corruption: %d of 400 loaded\n", loaded);
    CHECK(loaded > 50);
}

int main(void)
{
    RUN(test_names);
    RUN(test_not_threadsafe);
    RUN(test_load_registers);
    RUN(test_gpio);
    RUN(test_watchdog_bite);
    RUN(test_io_error);
    RUN(test_encoder);
    RUN(test_encoder_probe);
    RUN(test_stepgen);
    RUN(test_pwmgen);
    RUN(test_led_raw_queued);
    RUN(test_failures);
    RUN(test_random_corruption_full);
    tlog_clear(&lg);
    return check_summary();
}
