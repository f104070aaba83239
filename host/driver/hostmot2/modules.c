/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The module drivers the core runs, in the order it runs them: IOPort first
 * (the other modules' pins hang off it), the watchdog next. */
#include "modules.h"

extern const struct hm2_module_ops hm2_ioport_ops, hm2_watchdog_ops, hm2_encoder_ops,
    hm2_stepgen_ops, hm2_pwmgen_ops, hm2_led_ops, hm2_sserial_ops, hm2_raw_ops;

const struct hm2_module_ops *const hm2_modules[] = {
    &hm2_ioport_ops, &hm2_watchdog_ops, &hm2_encoder_ops, &hm2_stepgen_ops,
    &hm2_pwmgen_ops, &hm2_led_ops,      &hm2_sserial_ops, &hm2_raw_ops,
};
const int hm2_num_modules = (int)(sizeof(hm2_modules) / sizeof(hm2_modules[0]));
