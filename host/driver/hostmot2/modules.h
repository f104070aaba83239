/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The table of module drivers (modules.c) and the few module services the
 * core needs beyond the common operations: GPIO-only transfers (ioport.c)
 * and watchdog state for recovery and unload (watchdog.c). */
#ifndef HM2_MODULES_H
#define HM2_MODULES_H

#include "module_api.h"

extern const struct hm2_module_ops *const hm2_modules[];
extern const int hm2_num_modules;

/* IOPort: the GPIO data alone (read_gpio/write_gpio functions). */
int hm2_ioport_read_gpio(hostmot2_t *hm2);
int hm2_ioport_write_gpio(hostmot2_t *hm2);

/* Watchdog */
int hm2_watchdog_pet(hostmot2_t *hm2);
bool hm2_watchdog_has_bit(const hostmot2_t *hm2);
void hm2_watchdog_clear_bite(hostmot2_t *hm2);
void hm2_watchdog_force_bite(hostmot2_t *hm2);

#endif
