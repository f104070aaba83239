/* SPDX-License-Identifier: GPL-2.0-or-later */
/* epp_sim_open when the build has no virtual-board client library
 * (host/driver/backends/sim): the sim: port kind is then unavailable. */
#include <errno.h>
#include <stdio.h>

#include "hm2/epp_port.h"

int epp_sim_open(epp_port_t *port, const char *socket_path, int wide, char *err, size_t errlen)
{
    (void)port, (void)wide;
    snprintf(err, errlen, "sim:%s: this build has no virtual-board client library", socket_path);
    return -ENOSYS;
}
