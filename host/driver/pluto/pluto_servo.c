/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_servo - HAL driver for the Pluto-P board with the pluto_servo
 * firmware: 4 encoders, 4 PWM, 20 inputs, 18 outputs (docs/pluto_servo.md,
 * spec/pluto.md §3, §4, §7, §8).  loadrt arguments as LinuxCNC's, plus
 * port= (backend choice) and firmware= (the file uploaded at load).
 */
#include <stddef.h>

#include "hal.h"
#include "pluto_drivers.h"
#include "pluto_module.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("Hardware driver and firmware for the Pluto-P parallel-port FPGA, for use "
                   "with servos.");

PLUTO_MODULE_PARAMS("pluto_servo.rbf");
static int test_encoder = 0;
RTAPI_MP_INT(test_encoder, "Internally connect dout0..2 to QA0, QB0, QZ0 to test quadrature");

#define PFX "pluto-servo"

/* Lives in HAL memory; the pointer is how rtapi_app_exit finds it. */
struct servo_block {
    struct pluto_servo s;
    epp_port_t port;
};
static void *blk;
static int comp_id = -1;

static void read_funct(void *arg, long period)
{
    pluto_servo_read(&((struct servo_block *)arg)->s, period);
}

static void write_funct(void *arg, long period)
{
    pluto_servo_write(&((struct servo_block *)arg)->s, period);
}

static int export_encoders(struct pluto_servo *s, int id)
{
    int r = 0, i;
    for (i = 0; i < 4 && !r; i++) {
        r = hal_pin_s32_newf(HAL_OUT, &s->enc_count[i], id, PFX ".encoder.%d.count", i);
        if (!r)
            r = hal_pin_float_newf(HAL_OUT, &s->enc_position[i], id, PFX ".encoder.%d.position",
                                   i);
        if (!r)
            r = hal_pin_float_newf(HAL_OUT, &s->enc_velocity[i], id, PFX ".encoder.%d.velocity",
                                   i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &s->enc_reset[i], id, PFX ".encoder.%d.reset", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IO, &s->enc_index_enable[i], id,
                                 PFX ".encoder.%d.index-enable", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->enc_scale[i], id, PFX ".encoder.%d.scale", i);
    }
    if (!r)
        r = hal_param_bit_newf(HAL_RW, &s->z_polarity, id, PFX ".encoder.z-polarity");
    return r;
}

static int export_pwms(struct pluto_servo *s, int id)
{
    int r = 0, i;
    for (i = 0; i < 4 && !r; i++) {
        r = hal_pin_float_newf(HAL_IN, &s->pwm_value[i], id, PFX ".pwm.%d.value", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &s->pwm_enable[i], id, PFX ".pwm.%d.enable", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->pwm_offset[i], id, PFX ".pwm.%d.offset", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->pwm_scale[i], id, PFX ".pwm.%d.scale", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->pwm_max_dc[i], id, PFX ".pwm.%d.max-dc", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->pwm_min_dc[i], id, PFX ".pwm.%d.min-dc", i);
        if (!r)
            r = hal_param_bit_newf(HAL_RW, &s->pwm_pwmdir[i], id, PFX ".pwm.%d.pwmdir", i);
    }
    if (!r)
        r = hal_param_bit_newf(HAL_RW, &s->is_pdm, id, PFX ".pwm.is-pdm");
    return r;
}

static int init(void *block, int id)
{
    struct servo_block *b = block;
    struct pluto_servo *s = &b->s;
    s->port = &b->port;
    s->watchdog = watchdog ? 1 : 0;
    s->test_encoder = test_encoder ? 1 : 0;
    s->log.fn = pluto_rtapi_log;
    int r = export_encoders(s, id);
    if (!r)
        r = export_pwms(s, id);
    if (!r)
        r = pluto_export_dio(id, PFX, s->dout, s->dout_invert, 20, s->din, s->din_not, 20);
    if (!r)
        r = pluto_export_diag(id, PFX, &s->communication_error, &s->debug_0, &s->debug_1);
    if (!r)
        pluto_servo_defaults(s);
    return r;
}

static const struct pluto_module_desc desc = {
    .modname = "pluto_servo",
    .board = PFX,
    .default_firmware = "pluto_servo.rbf",
    .block_size = sizeof(struct servo_block),
    .port_offset = offsetof(struct servo_block, port),
    .init = init,
    .read = read_funct,
    .write = write_funct,
};

int rtapi_app_main(void)
{
    struct pluto_module_args a = {port, ioaddr, ioaddr_hi, epp_wide, firmware};
    return pluto_module_load(&desc, &a, &blk, &comp_id);
}

void rtapi_app_exit(void)
{
    pluto_module_unload(&desc, &blk, &comp_id);
}
