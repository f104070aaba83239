/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_servo - HAL driver for the Pluto-P board with the pluto_servo
 * firmware: 4 encoders, 4 PWM, 20 inputs, 18 outputs (docs/pluto_servo.md,
 * spec/pluto.md §3, §4, §7, §8).  loadrt arguments as LinuxCNC's, plus
 * port= (backend choice) and firmware= (the file uploaded at load).
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "hal.h"
#include "pluto_drivers.h"
#include "pluto_module.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("Hardware driver and firmware for the Pluto-P parallel-port FPGA, for use "
                   "with servos.");

static int ioaddr = 0x378;
RTAPI_MP_INT(ioaddr, "Address of parallel port where pluto-p is attached");
static int ioaddr_hi = 0;
RTAPI_MP_INT(ioaddr_hi, "Secondary address of parallel port (0 = ioaddr+0x400, -1 = none)");
static int epp_wide = 1;
RTAPI_MP_INT(epp_wide, "Use 16- and 32-bit EPP transfers with hardware EPP");
static int watchdog = 1;
RTAPI_MP_INT(watchdog, "Enable hardware watchdog to tristate outputs if EMC crashes");
static int test_encoder = 0;
RTAPI_MP_INT(test_encoder, "Internally connect dout0..2 to QA0, QB0, QZ0 to test quadrature");
static char *port = NULL;
RTAPI_MP_STRING(port, "Port: raw:ADDR, ppdev:/dev/parportN, gpiod:CHIP:LINES or sim:SOCKET "
                      "(overrides ioaddr)");
static char *firmware = NULL;
RTAPI_MP_STRING(firmware, "Firmware file uploaded at load (default pluto_servo.rbf on the "
                          "firmware path)");

#define PFX "pluto-servo"

/* Lives in HAL memory; the pointer is how rtapi_app_exit finds it. */
struct servo_block {
    struct pluto_servo s;
    epp_port_t port;
};
static struct servo_block *blk;
static int comp_id = -1;

static void read_funct(void *arg, long period)
{
    pluto_servo_read(&((struct servo_block *)arg)->s, period);
}

static void write_funct(void *arg, long period)
{
    pluto_servo_write(&((struct servo_block *)arg)->s, period);
}

static int export_all(struct pluto_servo *s)
{
    int r = 0, i;
    for (i = 0; i < 4 && !r; i++) {
        r = hal_pin_s32_newf(HAL_OUT, &s->enc_count[i], comp_id, PFX ".encoder.%d.count", i);
        if (!r)
            r = hal_pin_float_newf(HAL_OUT, &s->enc_position[i], comp_id,
                                   PFX ".encoder.%d.position", i);
        if (!r)
            r = hal_pin_float_newf(HAL_OUT, &s->enc_velocity[i], comp_id,
                                   PFX ".encoder.%d.velocity", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &s->enc_reset[i], comp_id, PFX ".encoder.%d.reset", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IO, &s->enc_index_enable[i], comp_id,
                                 PFX ".encoder.%d.index-enable", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->enc_scale[i], comp_id, PFX ".encoder.%d.scale",
                                     i);
    }
    if (!r)
        r = hal_param_bit_newf(HAL_RW, &s->z_polarity, comp_id, PFX ".encoder.z-polarity");
    for (i = 0; i < 4 && !r; i++) {
        r = hal_pin_float_newf(HAL_IN, &s->pwm_value[i], comp_id, PFX ".pwm.%d.value", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &s->pwm_enable[i], comp_id, PFX ".pwm.%d.enable", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->pwm_offset[i], comp_id, PFX ".pwm.%d.offset",
                                     i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->pwm_scale[i], comp_id, PFX ".pwm.%d.scale", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->pwm_max_dc[i], comp_id, PFX ".pwm.%d.max-dc",
                                     i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->pwm_min_dc[i], comp_id, PFX ".pwm.%d.min-dc",
                                     i);
        if (!r)
            r = hal_param_bit_newf(HAL_RW, &s->pwm_pwmdir[i], comp_id, PFX ".pwm.%d.pwmdir", i);
    }
    if (!r)
        r = hal_param_bit_newf(HAL_RW, &s->is_pdm, comp_id, PFX ".pwm.is-pdm");
    for (i = 0; i < 20 && !r; i++) {
        r = hal_pin_bit_newf(HAL_IN, &s->dout[i], comp_id, PFX ".dout.%02d", i);
        if (!r)
            r = hal_param_bit_newf(HAL_RW, &s->dout_invert[i], comp_id, PFX ".dout.%02d-invert",
                                   i);
    }
    for (i = 0; i < 20 && !r; i++) {
        r = hal_pin_bit_newf(HAL_OUT, &s->din[i], comp_id, PFX ".din.%02d", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_OUT, &s->din_not[i], comp_id, PFX ".din.%02d-not", i);
    }
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &s->communication_error, comp_id,
                               PFX ".communication-error");
    if (!r)
        r = hal_param_s32_newf(HAL_RW, &s->debug_0, comp_id, PFX ".debug-0");
    if (!r)
        r = hal_param_s32_newf(HAL_RW, &s->debug_1, comp_id, PFX ".debug-1");
    if (!r)
        r = hal_export_functf(read_funct, blk, 1, 0, comp_id, PFX ".read");
    if (!r)
        r = hal_export_functf(write_funct, blk, 1, 0, comp_id, PFX ".write");
    return r;
}

static epp_port_t *port_of(void *block)
{
    return &((struct servo_block *)block)->port;
}

static int init(void *block, int id)
{
    struct servo_block *b = block;
    struct pluto_servo *s = &b->s;
    blk = b; /* the functions' argument */
    comp_id = id;
    s->port = &b->port;
    s->watchdog = watchdog ? 1 : 0;
    s->test_encoder = test_encoder ? 1 : 0;
    s->log.fn = pluto_rtapi_log;
    int r = export_all(s);
    if (!r)
        pluto_servo_defaults(s);
    return r;
}

static const struct pluto_module_desc desc = {
    .modname = "pluto_servo",
    .board = "pluto-servo",
    .default_firmware = "pluto_servo.rbf",
    .block_size = sizeof(struct servo_block),
    .port_of = port_of,
    .init = init,
};

int rtapi_app_main(void)
{
    struct pluto_module_args a = {port, ioaddr, ioaddr_hi, epp_wide, firmware};
    void *b;
    int r = pluto_module_load(&desc, &a, &b, &comp_id);
    blk = r ? NULL : b;
    return r;
}

void rtapi_app_exit(void)
{
    void *b = blk;
    pluto_module_unload(&desc, &b, &comp_id);
    blk = NULL;
}
