/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The `hostmot2` realtime module: modparams, message sink, and the
 * exported hm2_register/hm2_unregister that board drivers call. */
#include <stdio.h>

#include "hm2/hostmot2.h"
#include "hm2_hal.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("Driver for HostMot2 firmware on Mesa Anything-I/O style boards");

/* Module parameters: the one kind of global state allowed. */
static int debug_idrom = 0;
RTAPI_MP_INT(debug_idrom, "Developer/debug use only!  Enable debug logging of the HostMot2 IDROM header.");
static int debug_module_descriptors = 0;
RTAPI_MP_INT(debug_module_descriptors, "Developer/debug use only!  Enable debug logging of the HostMot2 Module Descriptors.");
static int debug_pin_descriptors = 0;
RTAPI_MP_INT(debug_pin_descriptors, "Developer/debug use only!  Enable debug logging of the HostMot2 Pin Descriptors.");
static int debug_modules = 0;
RTAPI_MP_INT(debug_modules, "Developer/debug use only!  Enable debug logging of the HostMot2 Modules used.");
static int use_serial_numbers = 0;
RTAPI_MP_INT(use_serial_numbers, "Name cards by their serial number (accepted for compatibility; not used)");
static int sserial_baudrate = -1;
RTAPI_MP_INT(sserial_baudrate, "Over-ride the standard smart-serial baud rate (accepted for compatibility; not used)");
static char *firmware_path = NULL;
RTAPI_MP_STRING(firmware_path, "Colon-separated firmware search path (default $HM2_FIRMWARE_PATH, else $HM_BUILD/lib/firmware, the build's lib/firmware and /lib/firmware)");

static int comp_id;

static void rtapi_sink(void *ctx, int level, const char *line)
{
    (void)ctx;
    if (level == HM2_PRINT)
        rtapi_print("%s\n", line);
    else
        rtapi_print_msg((msg_level_t)level, "%s\n", line);
}

RTAPI_EXPORT int hm2_register(hm2_llio_t *llio, const char *config)
{
    struct hm2_hal_options o = {
        .opts = {.debug = {debug_idrom, debug_module_descriptors, debug_pin_descriptors,
                           debug_modules},
                 .firmware_path = firmware_path},
        .log = rtapi_sink,
        .log_ctx = NULL,
    };
    return hm2_register_opts(llio, config, &o);
}

RTAPI_EXPORT void hm2_unregister(hm2_llio_t *llio)
{
    hm2_unregister_board(llio);
}

int rtapi_app_main(void)
{
    rtapi_print("hm2: loading Mesa HostMot2 driver version %s\n", HM2_VERSION);
    comp_id = hal_init("hostmot2");
    if (comp_id < 0)
        return comp_id;
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void)
{
    hal_exit(comp_id);
    rtapi_print("hm2: unloading\n");
}
