/* SPDX-License-Identifier: GPL-2.0-or-later */
/* The port kinds epp_port_open knows, in the order the unknown-kind message
 * lists them.  A new backend adds its epp_port_kind here. */
#include "hm2/epp_port.h"

const struct epp_port_kind *const epp_port_kinds[] = {
    &epp_raw_kind,
    &epp_ppdev_kind,
    &epp_gpiod_kind,
    &epp_sim_kind,
};
const size_t epp_num_port_kinds = sizeof(epp_port_kinds) / sizeof(epp_port_kinds[0]);
