/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_dump - runs random scenarios through pluto_servo/pluto_step's read
 * and write (over the register model of tests/unit/epp/fakes.c) and prints
 * every input and output as JSON lines, for tests/e2e/pluto/test_model.py,
 * which recomputes the outputs with an independent Python model of
 * spec/pluto.md §4 and §6.
 *
 *   pluto_dump SEED STEPS
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../epp/fakes.h"
#include "pluto_drivers.h"

static uint64_t rs;
static uint64_t xr(void)
{
    rs ^= rs << 13;
    rs ^= rs >> 7;
    rs ^= rs << 17;
    return rs;
}
static double urand(double lo, double hi)
{
    return lo + (hi - lo) * (double)(xr() >> 11) / 9007199254740992.0;
}
static int coin(int pct)
{
    return (int)(xr() % 100) < pct;
}

static void nolog(void *ctx, int level, const char *fmt, ...)
{
    (void)ctx, (void)level, (void)fmt;
}

static void servo(int steps)
{
    static struct periph P;
    static struct pcport PC;
    epp_port_t port;
    periph_init(&P, PERIPH_PLUTO);
    P.trace_on = 0;
    pcport_init(&PC, &P);
    fake_batch_open(&port, &PC, 1);
    static struct pluto_servo s;
    static hal_s32_t cnt[4];
    static hal_float_t pos[4], vel[4], val[4];
    static hal_bit_t rst[4], idx[4], en[4], dout[20], din[20], dinn[20];
    memset(&s, 0, sizeof(s));
    for (int i = 0; i < 4; i++) {
        s.enc_count[i] = &cnt[i];
        s.enc_position[i] = &pos[i];
        s.enc_velocity[i] = &vel[i];
        s.enc_reset[i] = &rst[i];
        s.enc_index_enable[i] = &idx[i];
        s.pwm_value[i] = &val[i];
        s.pwm_enable[i] = &en[i];
    }
    for (int i = 0; i < 20; i++) {
        s.dout[i] = &dout[i];
        s.din[i] = &din[i];
        s.din_not[i] = &dinn[i];
    }
    pluto_servo_defaults(&s);
    s.port = &port;
    s.log.fn = nolog;
    uint32_t hwcount[4] = {0, 0, 0, 0};
    for (int k = 0; k < steps; k++) {
        long period = coin(80) ? 1000000 : 250000 + (long)(xr() % 2000000);
        s.watchdog = coin(80);
        s.test_encoder = coin(10);
        s.z_polarity = coin(20);
        s.is_pdm = coin(20);
        for (int i = 0; i < 4; i++) {
            val[i] = coin(5) ? 0.0 : urand(-3, 3);
            en[i] = coin(85);
            s.pwm_scale[i] = coin(70) ? urand(0.5, 2.5) * (coin(10) ? -1 : 1) : 1.0;
            s.pwm_offset[i] = coin(70) ? 0.0 : urand(-0.3, 0.3);
            s.pwm_max_dc[i] = coin(60) ? 1.0 : urand(-0.2, 1.3);
            s.pwm_min_dc[i] = coin(60) ? 0.0 : urand(-0.1, 0.5);
            s.pwm_pwmdir[i] = coin(50);
            s.enc_scale[i] = coin(50) ? 1.0 : urand(0.1, 1000);
            if (coin(30))
                idx[i] = 1;
            rst[i] = coin(5);
            int32_t d = (int32_t)(xr() % 16383) - 8191;
            hwcount[i] = (hwcount[i] + (uint32_t)d) & 0x3FFF;
            uint32_t latched = (uint32_t)(xr() & 0x3FFF);
            int indexed = coin(15);
            P.rreg[i] = hwcount[i] | latched << 14 | (indexed ? 1u << 28 : 0);
        }
        for (int i = 0; i < 20; i++) {
            dout[i] = coin(50);
            s.dout_invert[i] = coin(20);
        }
        P.rreg[4] = (uint32_t)(xr() & 0xFFFFF);
        printf("{\"drv\":\"servo\",\"k\":%d,\"period\":%ld,\"wd\":%d,\"te\":%d,\"zp\":%d,"
               "\"pdm\":%d,\"words\":[%u,%u,%u,%u,%u]",
               k, period, s.watchdog, s.test_encoder, (int)s.z_polarity, (int)s.is_pdm,
               P.rreg[0], P.rreg[1], P.rreg[2], P.rreg[3], P.rreg[4]);
        printf(",\"ch\":[");
        for (int i = 0; i < 4; i++)
            printf("%s{\"val\":%.17g,\"en\":%d,\"scale\":%.17g,\"off\":%.17g,\"max\":%.17g,"
                   "\"min\":%.17g,\"dir\":%d,\"escale\":%.17g,\"idx\":%d,\"rst\":%d}",
                   i ? "," : "", val[i], (int)en[i], s.pwm_scale[i], s.pwm_offset[i],
                   s.pwm_max_dc[i], s.pwm_min_dc[i], (int)s.pwm_pwmdir[i], s.enc_scale[i],
                   (int)idx[i], (int)rst[i]);
        printf("],\"dout\":[");
        for (int i = 0; i < 20; i++)
            printf("%s%d", i ? "," : "", (int)dout[i] ^ (int)s.dout_invert[i]);
        printf("]");
        pluto_servo_read(&s, period);
        pluto_servo_write(&s, period);
        printf(",\"out\":{\"count\":[%d,%d,%d,%d],\"pos\":[%.17g,%.17g,%.17g,%.17g],"
               "\"vel\":[%.17g,%.17g,%.17g,%.17g],\"idx\":[%d,%d,%d,%d],"
               "\"wreg\":[%u,%u,%u,%u,%u],\"din\":%u,\"max\":[%.17g,%.17g,%.17g,%.17g],"
               "\"min\":[%.17g,%.17g,%.17g,%.17g]}}\n",
               cnt[0], cnt[1], cnt[2], cnt[3], pos[0], pos[1], pos[2], pos[3], vel[0], vel[1],
               vel[2], vel[3], (int)idx[0], (int)idx[1], (int)idx[2], (int)idx[3], P.wreg[0],
               P.wreg[1], P.wreg[2], P.wreg[3], P.wreg[4],
               (unsigned)(din[0] | din[7] << 7 | din[19] << 19), s.pwm_max_dc[0],
               s.pwm_max_dc[1], s.pwm_max_dc[2], s.pwm_max_dc[3], s.pwm_min_dc[0],
               s.pwm_min_dc[1], s.pwm_min_dc[2], s.pwm_min_dc[3]);
    }
    epp_port_close(&port);
}

static void step(int steps)
{
    static struct periph P;
    static struct pcport PC;
    epp_port_t port;
    periph_init(&P, PERIPH_PLUTO);
    P.trace_on = 0;
    P.pluto_step = 1;
    pcport_init(&PC, &P);
    fake_batch_open(&port, &PC, 1);
    static struct pluto_step t;
    static hal_float_t cmd[4], vfb[4], pfb[4];
    static hal_s32_t counts[4];
    static hal_bit_t en[4], rst[4], dout[14], din[16], dinn[16];
    memset(&t, 0, sizeof(t));
    for (int i = 0; i < 4; i++) {
        t.position_cmd[i] = &cmd[i];
        t.velocity_fb[i] = &vfb[i];
        t.position_fb[i] = &pfb[i];
        t.counts[i] = &counts[i];
        t.enable[i] = &en[i];
        t.reset[i] = &rst[i];
    }
    for (int i = 0; i < 14; i++)
        t.dout[i] = &dout[i];
    for (int i = 0; i < 16; i++) {
        t.din[i] = &din[i];
        t.din_not[i] = &dinn[i];
    }
    pluto_step_defaults(&t);
    t.port = &port;
    t.log.fn = nolog;
    t.speedrange = (int)(xr() % 4);
    uint32_t hw[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; i++)
        t.scale[i] = urand(10, 5000) * (coin(20) ? -1 : 1);
    for (int k = 0; k < steps; k++) {
        long period = coin(80) ? 1000000 : 250000 + (long)(xr() % 2000000);
        t.watchdog = coin(70);
        if (coin(10)) {
            t.steplen = (uint32_t)(xr() % 60000);
            t.stepspace = (uint32_t)(xr() % 60000);
            t.dirtime = (uint32_t)(xr() % 60000);
        }
        t.step_polarity = coin(30);
        if (coin(5))
            t.debug_2 = urand(0, 1);
        for (int i = 0; i < 4; i++) {
            cmd[i] += urand(-0.05, 0.05);
            en[i] = coin(90);
            rst[i] = coin(3);
            if (coin(5))
                t.maxvel[i] = coin(50) ? 0 : urand(-500, 500);
            int32_t d = (int32_t)(xr() % 2000000) - 1000000;
            hw[i] = (hw[i] + (uint32_t)d) & 0x1FFFFF;
            P.rreg[i] = hw[i] | (uint32_t)(xr() & 0xFFE00000u);
        }
        for (int i = 0; i < 14; i++) {
            dout[i] = coin(50);
            t.dout_invert[i] = coin(20);
        }
        P.rreg[4] = (uint32_t)xr();
        printf("{\"drv\":\"step\",\"k\":%d,\"period\":%ld,\"sr\":%d,\"wd\":%d,\"pol\":%d,"
               "\"steplen\":%u,\"stepspace\":%u,\"dirtime\":%u,\"gain\":%.17g,"
               "\"words\":[%u,%u,%u,%u,%u]",
               k, period, t.speedrange, t.watchdog, (int)t.step_polarity, t.steplen, t.stepspace,
               t.dirtime, t.debug_2, P.rreg[0], P.rreg[1], P.rreg[2], P.rreg[3], P.rreg[4]);
        printf(",\"ch\":[");
        for (int i = 0; i < 4; i++)
            printf("%s{\"cmd\":%.17g,\"en\":%d,\"rst\":%d,\"scale\":%.17g,\"maxvel\":%.17g}",
                   i ? "," : "", cmd[i], (int)en[i], (int)rst[i], t.scale[i], t.maxvel[i]);
        printf("],\"dout\":[");
        for (int i = 0; i < 14; i++)
            printf("%s%d", i ? "," : "", (int)dout[i] ^ (int)t.dout_invert[i]);
        printf("]");
        pluto_step_read(&t, period);
        pluto_step_write(&t, period);
        printf(",\"out\":{\"counts\":[%d,%d,%d,%d],\"pfb\":[%.17g,%.17g,%.17g,%.17g],"
               "\"vfb\":[%.17g,%.17g,%.17g,%.17g],\"wreg\":[%u,%u,%u,%u,%u,%u],"
               "\"maxvel\":[%.17g,%.17g,%.17g,%.17g],\"steplen\":%u,\"dirtime\":%u,"
               "\"din\":%u}}\n",
               counts[0], counts[1], counts[2], counts[3], pfb[0], pfb[1], pfb[2], pfb[3],
               vfb[0], vfb[1], vfb[2], vfb[3], P.wreg[0], P.wreg[1], P.wreg[2], P.wreg[3],
               P.wreg[4], P.wreg[5], t.maxvel[0], t.maxvel[1], t.maxvel[2], t.maxvel[3],
               t.steplen, t.dirtime, (unsigned)(din[0] | din[15] << 15));
    }
    epp_port_close(&port);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: pluto_dump SEED STEPS\n");
        return 2;
    }
    rs = strtoull(argv[1], NULL, 0) | 1;
    int steps = atoi(argv[2]);
    servo(steps);
    step(steps);
    return 0;
}
