/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_step - HAL driver for the Pluto-P board with the pluto_step
 * firmware: 4 step generators, 16 inputs, 14 outputs (docs/pluto_step.md,
 * spec/pluto.md §5, §6, §7, §8).  loadrt arguments as LinuxCNC's, plus
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
                   "with steppers.");

static int ioaddr = 0x378;
RTAPI_MP_INT(ioaddr, "Address of parallel port where pluto-p is attached");
static int ioaddr_hi = 0;
RTAPI_MP_INT(ioaddr_hi, "Secondary address of parallel port (0 = ioaddr+0x400, -1 = none)");
static int epp_wide = 1;
RTAPI_MP_INT(epp_wide, "Use 16- and 32-bit EPP transfers with hardware EPP");
static int watchdog = 1;
RTAPI_MP_INT(watchdog, "Enable hardware watchdog to tristate outputs if EMC crashes");
static int speedrange = 0;
RTAPI_MP_INT(speedrange, "Selects one of four speed ranges: 0: Top speed 312.5kHz; minimum "
                         "speed 610Hz; 1: 156.25kHz, 305Hz; 2: 78.125kHz, 153Hz; 3: 39.06kHz, "
                         "76Hz");
static char *port = NULL;
RTAPI_MP_STRING(port, "Port: raw:ADDR, ppdev:/dev/parportN, gpiod:CHIP:LINES or sim:SOCKET "
                      "(overrides ioaddr)");
static char *firmware = NULL;
RTAPI_MP_STRING(firmware, "Firmware file uploaded at load (default pluto_step.rbf on the "
                          "firmware path)");

#define PFX "pluto-step"

struct step_block {
    struct pluto_step s;
    epp_port_t port;
};
static struct step_block *blk;
static int comp_id = -1;

static void read_funct(void *arg, long period)
{
    pluto_step_read(&((struct step_block *)arg)->s, period);
}

static void write_funct(void *arg, long period)
{
    pluto_step_write(&((struct step_block *)arg)->s, period);
}

static int export_all(struct pluto_step *s)
{
    int r = 0, i;
    for (i = 0; i < 4 && !r; i++) {
        r = hal_pin_float_newf(HAL_IN, &s->position_cmd[i], comp_id,
                               PFX ".stepgen.%d.position-cmd", i);
        if (!r)
            r = hal_pin_float_newf(HAL_OUT, &s->velocity_fb[i], comp_id,
                                   PFX ".stepgen.%d.velocity-fb", i);
        if (!r)
            r = hal_pin_float_newf(HAL_OUT, &s->position_fb[i], comp_id,
                                   PFX ".stepgen.%d.position-fb", i);
        if (!r)
            r = hal_pin_s32_newf(HAL_OUT, &s->counts[i], comp_id, PFX ".stepgen.%d.counts", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &s->enable[i], comp_id, PFX ".stepgen.%d.enable", i);
        if (!r)
            r = hal_pin_bit_newf(HAL_IN, &s->reset[i], comp_id, PFX ".stepgen.%d.reset", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->scale[i], comp_id, PFX ".stepgen.%d.scale", i);
        if (!r)
            r = hal_param_float_newf(HAL_RW, &s->maxvel[i], comp_id, PFX ".stepgen.%d.maxvel",
                                     i);
    }
    if (!r)
        r = hal_param_bit_newf(HAL_RW, &s->step_polarity, comp_id, PFX ".stepgen.step-polarity");
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &s->steplen, comp_id, PFX ".stepgen.steplen");
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &s->stepspace, comp_id, PFX ".stepgen.stepspace");
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &s->dirtime, comp_id, PFX ".stepgen.dirtime");
    for (i = 0; i < 14 && !r; i++) {
        r = hal_pin_bit_newf(HAL_IN, &s->dout[i], comp_id, PFX ".dout.%02d", i);
        if (!r)
            r = hal_param_bit_newf(HAL_RW, &s->dout_invert[i], comp_id, PFX ".dout.%02d-invert",
                                   i);
    }
    for (i = 0; i < 16 && !r; i++) {
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
        r = hal_param_float_newf(HAL_RW, &s->debug_2, comp_id, PFX ".debug-2");
    if (!r)
        r = hal_param_float_newf(HAL_RW, &s->debug_3, comp_id, PFX ".debug-3");
    if (!r)
        r = hal_export_functf(read_funct, blk, 1, 0, comp_id, PFX ".read");
    if (!r)
        r = hal_export_functf(write_funct, blk, 1, 0, comp_id, PFX ".write");
    return r;
}

static epp_port_t *port_of(void *block)
{
    return &((struct step_block *)block)->port;
}

static int init(void *block, int id)
{
    struct step_block *b = block;
    struct pluto_step *s = &b->s;
    blk = b; /* the functions' argument */
    comp_id = id;
    s->port = &b->port;
    s->speedrange = speedrange;
    s->watchdog = watchdog ? 1 : 0;
    s->log.fn = pluto_rtapi_log;
    int r = export_all(s);
    if (!r)
        pluto_step_defaults(s);
    return r;
}

static const struct pluto_module_desc desc = {
    .modname = "pluto_step",
    .board = "pluto-step",
    .default_firmware = "pluto_step.rbf",
    .block_size = sizeof(struct step_block),
    .port_of = port_of,
    .init = init,
};

int rtapi_app_main(void)
{
    if (speedrange < 0 || speedrange > 3) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pluto_step: speedrange=%d is out of range (0..3)\n",
                        speedrange);
        return -EINVAL;
    }
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
