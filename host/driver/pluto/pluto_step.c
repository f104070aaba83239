/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_step - HAL driver for the Pluto-P board with the pluto_step
 * firmware: 4 step generators, 16 inputs, 14 outputs (docs/pluto_step.md,
 * spec/pluto.md §5, §6, §7, §8).  loadrt arguments as LinuxCNC's, plus
 * port= (backend choice) and firmware= (the file uploaded at load).
 */
#include <errno.h>
#include <stddef.h>

#include "hal.h"
#include "pluto_drivers.h"
#include "pluto_module.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("Hardware driver and firmware for the Pluto-P parallel-port FPGA, for use "
                   "with steppers.");

PLUTO_MODULE_PARAMS("pluto_step.rbf");
static int speedrange = 0;
RTAPI_MP_INT(speedrange, "Selects one of four speed ranges: 0: Top speed 312.5kHz; minimum "
                         "speed 610Hz; 1: 156.25kHz, 305Hz; 2: 78.125kHz, 153Hz; 3: 39.06kHz, "
                         "76Hz");

#define PFX "pluto-step"

struct step_block {
    struct pluto_step s;
    epp_port_t port;
};
static void *blk;
static int comp_id = -1;

static void read_funct(void *arg, long period)
{
    pluto_step_read(&((struct step_block *)arg)->s, period);
}

static void write_funct(void *arg, long period)
{
    pluto_step_write(&((struct step_block *)arg)->s, period);
}

static int export_stepgens(struct pluto_step *s, int id)
{
    int r = 0, i;
    for (i = 0; i < 4 && !r; i++) {
        r = hal_pin_float_newf(HAL_IN, &s->position_cmd[i], id, PFX ".stepgen.%d.position-cmd",
                               i);
        if (!r)
            r = hal_pin_float_newf(HAL_OUT, &s->velocity_fb[i], id,
                                   PFX ".stepgen.%d.velocity-fb", i);
        if (!r)
            r = hal_pin_float_newf(HAL_OUT, &s->position_fb[i], id,
                                   PFX ".stepgen.%d.position-fb", i);
        if (!r)
            r = hal_pin_s32_newf(HAL_OUT, &s->counts[i], id, PFX ".stepgen.%d.counts", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &s->enable[i], id, PFX ".stepgen.%d.enable", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &s->reset[i], id, PFX ".stepgen.%d.reset", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->scale[i], id, PFX ".stepgen.%d.scale", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->maxvel[i], id, PFX ".stepgen.%d.maxvel", i);
    }
    if (!r)
        r = hal_param_bit_newf(HAL_RW, &s->step_polarity, id, PFX ".stepgen.step-polarity");
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &s->steplen, id, PFX ".stepgen.steplen");
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &s->stepspace, id, PFX ".stepgen.stepspace");
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &s->dirtime, id, PFX ".stepgen.dirtime");
    return r;
}

static int init(void *block, int id)
{
    struct step_block *b = block;
    struct pluto_step *s = &b->s;
    s->port = &b->port;
    s->speedrange = speedrange;
    s->watchdog = watchdog ? 1 : 0;
    s->log.fn = pluto_rtapi_log;
    int r = export_stepgens(s, id);
    if (!r)
        r = pluto_export_dio(id, PFX, s->dout, s->dout_invert, 14, s->din, s->din_not, 16);
    if (!r)
        r = pluto_export_diag(id, PFX, &s->communication_error, &s->debug_0, &s->debug_1);
    if (!r)
        r = hal_param_float_newf(HAL_RW, &s->debug_2, id, PFX ".debug-2");
    if (!r)
        r = hal_param_float_newf(HAL_RW, &s->debug_3, id, PFX ".debug-3");
    if (!r)
        pluto_step_defaults(s);
    return r;
}

static const struct pluto_module_desc desc = {
    .modname = "pluto_step",
    .board = PFX,
    .default_firmware = "pluto_step.rbf",
    .block_size = sizeof(struct step_block),
    .port_offset = offsetof(struct step_block, port),
    .init = init,
    .read = read_funct,
    .write = write_funct,
};

int rtapi_app_main(void)
{
    if (speedrange < 0 || speedrange > 3) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pluto_step: speedrange=%d is out of range (0..3)\n",
                        speedrange);
        return -EINVAL;
    }
    struct pluto_module_args a = {port, ioaddr, ioaddr_hi, epp_wide, firmware};
    return pluto_module_load(&desc, &a, &blk, &comp_id);
}

void rtapi_app_exit(void)
{
    pluto_module_unload(&desc, &blk, &comp_id);
}
