/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * probe_parport - accepted so that HAL files written for LinuxCNC load
 * unchanged (docs/probe_parport.md).  In LinuxCNC's kernel builds it asked
 * the kernel's PnP layer to configure parallel ports; in userspace the
 * kernel's parport_pc driver does that, so, as the seed says of machines
 * without PnP ports, it loads and has no effect.  It creates no HAL objects
 * but registers a component so that `show comp` lists it and `unloadrt`
 * finds it.
 */
#include "hal.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("PnP parallel port probe (no effect: Linux configures PnP ports)");

static int comp_id;

int rtapi_app_main(void)
{
    comp_id = hal_init("probe_parport");
    if (comp_id < 0)
        return comp_id;
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
}
