/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * Parameter sanitizing of the hostmot2 modules, one test per sanitized
 * parameter, against the LinuxCNC 2.9 behaviour documented in hostmot2(9)
 * and spec/hostmot2.md §10 (expected values computed by hand here): each bad
 * value gets an error naming the object, the parameter is rewritten to what
 * the driver uses, and the registers follow the rewritten value.  Also the
 * module descriptors the driver refuses (encoder + muxed encoder, StepGen
 * v0xC2) and the watchdog defaults kept from the seed.
 *
 * Not sanitized (as in 2.9): the GPIO bits (is_output, is_opendrain,
 * invert_output) and the LED pins take any value; encoder vel-timeout is
 * used as given.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../check.h"
#include "../../../host/driver/hostmot2/hm2_hal.h"
#include "fake_hal.h"
#include "hm2/boards.h"
#include "testlib.h"

static struct hm2_image_llio im;
static struct tlog lg;
#define PFX "hm2_5i20.0"
#define PERIOD 1000000L
#define CLOCK_LOW 33333333.0
#define CLOCK_HIGH 100000000.0
#define MD_BASE (T_IDROM + T_MD_OFF)

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
    int r = do_register(config);
    CHECK_EQ_INT(r, 0);
    if (r)
        tlog_dump(&lg);
}

static uint32_t reg(uint32_t addr)
{
    return hm2_image_get32(&im, addr);
}

static void done(void)
{
    hm2_unregister_board(&im.llio);
}

/* ---- StepGen ------------------------------------------------------------ */

/* A negative maxaccel used to flip the ramp: velocity-fb grew without bound
 * away from the command.  2.9 takes its absolute value. */
static void test_stepgen_maxaccel_negative(void)
{
    setup("num_stepgens=1");
    *fake_float(PFX ".stepgen.00.position-scale") = 100.0;
    *fake_float(PFX ".stepgen.00.maxaccel") = -50.0;
    *fake_bit(PFX ".stepgen.00.enable") = 1;
    *fake_float(PFX ".stepgen.00.position-cmd") = 1.0;
    double prev = 0.0;
    for (int k = 0; k < 200; k++) {
        fake_run(PFX ".read", PERIOD);
        fake_run(PFX ".write", PERIOD);
        double v = *fake_float(PFX ".stepgen.00.velocity-fb");
        /* ramps at most 50 units/s^2 * 1 ms per period, toward the command */
        CHECK(fabs(v - prev) <= 50.0 * 1e-3 + 1e-12);
        CHECK(v >= 0.0);
        prev = v;
    }
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.maxaccel"), 50.0, 0);
    CHECK(tlog_contains(&lg, "stepgen.00.maxaccel < 0, setting to its absolute value"));
    CHECK(prev > 0.0 && prev <= 200 * 50.0 * 1e-3 + 1e-9);
    /* velocity mode too */
    *fake_float(PFX ".stepgen.00.maxaccel") = -20.0;
    *fake_bit(PFX ".stepgen.00.control-type") = 1;
    *fake_float(PFX ".stepgen.00.velocity-cmd") = 10.0;
    double before = *fake_float(PFX ".stepgen.00.velocity-fb");
    fake_run(PFX ".write", PERIOD);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.maxaccel"), 20.0, 0);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.velocity-fb"), before + 20.0 * 1e-3, 1e-12);
    done();
}

static void test_stepgen_maxvel_negative(void)
{
    setup("num_stepgens=1");
    *fake_float(PFX ".stepgen.00.maxvel") = -3.0;
    *fake_float(PFX ".stepgen.00.maxaccel") = 0.0;
    *fake_bit(PFX ".stepgen.00.control-type") = 1;
    *fake_float(PFX ".stepgen.00.velocity-cmd") = -100.0;
    *fake_bit(PFX ".stepgen.00.enable") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.maxvel"), 3.0, 0);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.velocity-fb"), -3.0, 1e-12);
    CHECK(tlog_contains(&lg, "stepgen.00.maxvel < 0, setting to its absolute value"));
    done();
}

static void test_stepgen_maxvel_too_big(void)
{
    setup("num_stepgens=1");
    *fake_float(PFX ".stepgen.00.position-scale") = 400.0;
    *fake_u32(PFX ".stepgen.00.steplen") = 2000;
    *fake_u32(PFX ".stepgen.00.stepspace") = 3000;
    *fake_float(PFX ".stepgen.00.maxvel") = 1e6;
    fake_run(PFX ".write", PERIOD);
    double phys = 1e9 / 5000.0 / 400.0; /* 500 units/s */
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.maxvel"), phys, 1e-9);
    CHECK(tlog_contains(&lg, "stepgen.00.maxvel is too big for current step timings"));
    done();
}

static void test_stepgen_position_scale_zero(void)
{
    setup("num_stepgens=2");
    *fake_float(PFX ".stepgen.00.position-scale") = 0.0;
    *fake_float(PFX ".stepgen.01.position-scale") = -1e-9;
    hm2_image_put32(&im, 0x2100, 7u << 16);
    fake_run(PFX ".read", PERIOD);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.position-scale"), 1.0, 0);
    CHECK_NEAR(*fake_float(PFX ".stepgen.01.position-scale"), -1.0, 0);
    CHECK_NEAR(*fake_float(PFX ".stepgen.00.position-fb"), 7.0, 1e-12);
    CHECK(tlog_contains(&lg, "stepgen.00.position-scale is too close to 0, setting it to 1.0"));
    CHECK(tlog_contains(&lg, "stepgen.01.position-scale is too close to 0, setting it to -1.0"));
    done();
}

/* steplen, stepspace, dirsetup, dirhold: > 0x3FFF clocks -> 0x3FFF, the
 * parameter rewritten to that time in ns (491490 ns at 33.333333 MHz) */
static void timing_case(const char *param, uint32_t regbase)
{
    char name[96];
    snprintf(name, sizeof(name), PFX ".stepgen.01.%s", param);
    setup("num_stepgens=2");
    *fake_u32(name) = 1000000;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(regbase + 4), 0x3FFF);
    CHECK_EQ_INT(*fake_u32(name), (uint32_t)(0x3FFF * 1e9 / CLOCK_LOW));
    char msg[96];
    snprintf(msg, sizeof(msg), "stepgen.01.%s 1000000 ns is longer than the firmware", param);
    CHECK(tlog_contains(&lg, msg));
    /* in range: floor(ns * ClockLow / 1e9), not rewritten */
    *fake_u32(name) = 4000;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(regbase + 4), (uint32_t)floor(4000 * CLOCK_LOW / 1e9));
    CHECK_EQ_INT(*fake_u32(name), 4000);
    done();
}

static void test_stepgen_steplen(void)
{
    timing_case("steplen", 0x2500);
}
static void test_stepgen_stepspace(void)
{
    timing_case("stepspace", 0x2600);
}
static void test_stepgen_dirsetup(void)
{
    timing_case("dirsetup", 0x2300);
}
static void test_stepgen_dirhold(void)
{
    timing_case("dirhold", 0x2400);
}

static void test_stepgen_step_type(void)
{
    setup("num_stepgens=1");
    *fake_u32(PFX ".stepgen.00.step_type") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x2200), 1);
    *fake_u32(PFX ".stepgen.00.step_type") = 99;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x2200), 0);
    CHECK_EQ_INT(*fake_u32(PFX ".stepgen.00.step_type"), 0);
    CHECK(tlog_contains(&lg, "stepgen.00.step_type 99 is invalid"));
    done();
}

/* ---- Encoder ------------------------------------------------------------ */

static void test_encoder_scale_zero(void)
{
    setup("num_encoders=1");
    *fake_float(PFX ".encoder.00.scale") = 0.0;
    hm2_image_put32(&im, 0x3000, 40);
    fake_run(PFX ".read", PERIOD);
    CHECK_NEAR(*fake_float(PFX ".encoder.00.scale"), 1.0, 0);
    CHECK(tlog_contains(&lg, "encoder.00.scale is too close to 0, setting it to 1.0"));
    CHECK(isfinite(*fake_float(PFX ".encoder.00.position")));
    CHECK_NEAR(*fake_float(PFX ".encoder.00.position"), (double)*fake_s32(PFX ".encoder.00.count"),
               0);
    done();
}

static void test_encoder_sample_frequency(void)
{
    setup("num_encoders=1");
    /* 0 and anything at or above ClockLow: the filter runs at ClockLow */
    *fake_u32(PFX ".encoder.sample-frequency") = 0;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3400), 0xFFF);
    CHECK_EQ_INT(*fake_u32(PFX ".encoder.sample-frequency"), 33333333);
    /* too low for the 11-bit divider: the slowest rate, pin rewritten */
    *fake_u32(PFX ".encoder.sample-frequency") = 1000;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3400), 0x7FF);
    CHECK_EQ_INT(*fake_u32(PFX ".encoder.sample-frequency"), 33333333 / (0x7FF + 2));
    /* in range: rewritten to the frequency really used, ClockLow/(reg+2) */
    *fake_u32(PFX ".encoder.sample-frequency") = 3000000;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x3400), 33333333 / 3000000 - 2);
    CHECK_EQ_INT(*fake_u32(PFX ".encoder.sample-frequency"), 33333333 / (33333333 / 3000000));
    done();
}

/* ---- PWMGen ------------------------------------------------------------- */

static void test_pwmgen_scale_zero(void)
{
    setup("num_pwmgens=1");
    *fake_float(PFX ".pwmgen.00.scale") = 0.0;
    *fake_float(PFX ".pwmgen.00.value") = 0.25;
    *fake_bit(PFX ".pwmgen.00.enable") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK_NEAR(*fake_float(PFX ".pwmgen.00.scale"), 1.0, 0);
    CHECK(tlog_contains(&lg, "pwmgen.00.scale is 0, setting it to 1.0"));
    CHECK_EQ_INT(reg(0x4000), (uint32_t)(0.25 * 4095 * 65536)); /* 12 bits at 20 kHz */
    done();
}

static void test_pwmgen_pwm_frequency(void)
{
    setup("num_pwmgens=1");
    *fake_u32(PFX ".pwmgen.pwm_frequency") = 0;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(*fake_u32(PFX ".pwmgen.pwm_frequency"), 1);
    CHECK(tlog_contains(&lg, "pwmgen.pwm_frequency 0 Hz is too low, setting it to 1 Hz"));
    /* 1 Hz at 12 bits: floor(65536 * 4096 / 1e8) */
    CHECK_EQ_INT(reg(0x4200), (uint32_t)floor(65536.0 * 4096.0 / CLOCK_HIGH));
    CHECK_EQ_INT(reg(0x4100) & 3, 3);
    /* too high: ClockHigh * 65535 / (65536 * 512) */
    *fake_u32(PFX ".pwmgen.pwm_frequency") = 500000;
    fake_run(PFX ".write", PERIOD);
    uint32_t max = (uint32_t)(CLOCK_HIGH * 65535.0 / (65536.0 * 512.0));
    CHECK_EQ_INT(*fake_u32(PFX ".pwmgen.pwm_frequency"), max);
    CHECK_EQ_INT(reg(0x4200), 65535);
    CHECK(tlog_contains(&lg, "max PWM frequency is 195309 Hz"));
    done();
}

static void test_pwmgen_pdm_frequency(void)
{
    setup("num_pwmgens=1");
    *fake_u32(PFX ".pwmgen.pdm_frequency") = 0;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x4300), 1);
    CHECK_EQ_INT(*fake_u32(PFX ".pwmgen.pdm_frequency"), (uint32_t)(CLOCK_HIGH / 65536.0));
    CHECK(tlog_contains(&lg, "pwmgen.pdm_frequency 0 Hz is too low"));
    *fake_u32(PFX ".pwmgen.pdm_frequency") = 200000000;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x4300), 65535);
    CHECK_EQ_INT(*fake_u32(PFX ".pwmgen.pdm_frequency"),
                 (uint32_t)(65535.0 * CLOCK_HIGH / 65536.0));
    CHECK(tlog_contains(&lg, "pwmgen.pdm_frequency 200000000 Hz is too high"));
    done();
}

static void test_pwmgen_output_type(void)
{
    setup("num_pwmgens=1");
    *fake_s32(PFX ".pwmgen.00.output-type") = 0;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(*fake_s32(PFX ".pwmgen.00.output-type"), 1);
    CHECK_EQ_INT((reg(0x4100) >> 3) & 3, 0); /* PWM/Dir */
    CHECK(tlog_contains(&lg, "pwmgen.00.output-type 0 is invalid"));
    done();
}

/* ---- Watchdog ----------------------------------------------------------- */

static void test_watchdog_timeout_ns(void)
{
    setup(NULL);
    CHECK_EQ_INT(*fake_u32(PFX ".watchdog.timeout_ns"), 1000000000u); /* seed default, 1 s */
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x0C00), (uint32_t)(1e9 * CLOCK_LOW / 1e9 - 1));
    /* The range check (timer >= 2^31 clocks -> clipped, parameter rewritten)
     * cannot trigger at 33.333333 MHz: 2^31 clocks are 64.4 s, beyond the
     * largest u32 timeout (4.29 s), which is used as given. */
    *fake_u32(PFX ".watchdog.timeout_ns") = 4294967295u;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x0C00), (uint32_t)(4294967295.0 * CLOCK_LOW / 1e9 - 1.0));
    CHECK_EQ_INT(*fake_u32(PFX ".watchdog.timeout_ns"), 4294967295u);
    CHECK(!tlog_contains(&lg, "out of range"));
    bool clipped;
    /* at 1 GHz it can: 4294967295 ns = 4294967294 clocks -> 0x7FFFFFFF */
    CHECK_EQ_INT(hm2_watchdog_timer_value(4294967295u, 1000000000u, &clipped), 0x7FFFFFFFu);
    CHECK(clipped);
    CHECK_EQ_INT(hm2_watchdog_max_timeout_ns(1000000000u), 0x7FFFFFFFu);
    /* shorter than 1.5 periods: a warning, used as given */
    *fake_u32(PFX ".watchdog.timeout_ns") = 1000000;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(*fake_u32(PFX ".watchdog.timeout_ns"), 1000000);
    CHECK(tlog_contains(&lg, "Watchdog timeout (1000000 ns) is dangerously short"));
    done();
}

/* ---- module descriptors refused ----------------------------------------- */

static int md_index(uint8_t gtag)
{
    for (int i = 0; i < HM2_MAX_MODULE_DESCRIPTORS; i++)
        if ((reg(MD_BASE + 12u * (uint32_t)i) & 0xFF) == gtag)
            return i;
    return -1;
}

static void test_encoder_and_muxed_encoder(void)
{
    fake_hal_reset();
    t_setup_5i20(&im);
    /* the PWMGen MD has the muxed encoder's geometry (5 registers, MP 0x03):
     * turn it into a muxed encoder v3 beside the plain encoder */
    int i = md_index(HM2_GTAG_PWMGEN);
    CHECK(i >= 0);
    uint32_t a = MD_BASE + 12u * (uint32_t)i;
    hm2_image_put32(&im, a, (reg(a) & 0xFFFF0000u) | 3u << 8 | HM2_GTAG_MUXED_ENCODER);
    int objects = fake_hal_objects();
    CHECK_EQ_INT(do_register(NULL), -EINVAL);
    CHECK(tlog_contains(&lg, "found duplicate Module Descriptor for Muxed Encoder"));
    CHECK_EQ_INT(fake_hal_objects(), objects);
    CHECK(im.llio.hm2 == NULL);
}

static void test_stepgen_v0xc2_refused(void)
{
    fake_hal_reset();
    t_setup_5i20(&im);
    int i = md_index(HM2_GTAG_STEPGEN);
    CHECK(i >= 0);
    uint32_t a = MD_BASE + 12u * (uint32_t)i;
    hm2_image_put32(&im, a, (reg(a) & 0xFFFF00FFu) | 0xC2u << 8);
    int objects = fake_hal_objects();
    CHECK_EQ_INT(do_register(NULL), -EINVAL);
    CHECK(tlog_contains(&lg, "StepGen v0xC2 (index/probe position latching) is not supported"));
    CHECK_EQ_INT(fake_hal_objects(), objects);
    /* v0x42 (swap bit) loads and has swap_step_dir */
    fake_hal_reset();
    t_setup_5i20(&im);
    hm2_image_put32(&im, a, (reg(a) & 0xFFFF00FFu) | 0x42u << 8);
    CHECK_EQ_INT(do_register("num_stepgens=1"), 0);
    *fake_bit(PFX ".stepgen.00.swap_step_dir") = 1;
    *fake_u32(PFX ".stepgen.00.step_type") = 1;
    fake_run(PFX ".write", PERIOD);
    CHECK_EQ_INT(reg(0x2200), 1u | 1u << 2);
    done();
}

int main(void)
{
    RUN(test_stepgen_maxaccel_negative);
    RUN(test_stepgen_maxvel_negative);
    RUN(test_stepgen_maxvel_too_big);
    RUN(test_stepgen_position_scale_zero);
    RUN(test_stepgen_steplen);
    RUN(test_stepgen_stepspace);
    RUN(test_stepgen_dirsetup);
    RUN(test_stepgen_dirhold);
    RUN(test_stepgen_step_type);
    RUN(test_encoder_scale_zero);
    RUN(test_encoder_sample_frequency);
    RUN(test_pwmgen_scale_zero);
    RUN(test_pwmgen_pwm_frequency);
    RUN(test_pwmgen_pdm_frequency);
    RUN(test_pwmgen_output_type);
    RUN(test_watchdog_timeout_ns);
    RUN(test_encoder_and_muxed_encoder);
    RUN(test_stepgen_v0xc2_refused);
    return check_summary();
}
