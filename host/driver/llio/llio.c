/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Helpers every llio user shares: connector text and sanity checks. */
#include <errno.h>
#include <stdio.h>

#include "hm2/llio.h"

/* DB25 pin for each bit of a 17-pin port (5i25-style P3/P2). */
static const int db25_order[17] = {1, 14, 2, 15, 3, 16, 4, 17, 5, 6, 7, 8, 9, 10, 11, 12, 13};

const char *hm2_llio_pin_name(const hm2_llio_t *llio, int io_pin, char *buf, size_t len)
{
    if (llio->io_pin_names && io_pin >= 0 && io_pin < llio->num_io_pin_names)
        return llio->io_pin_names[io_pin];
    int width = llio->pins_per_connector;
    if (width <= 0 || io_pin < 0)
        return NULL;
    int port = io_pin / width;
    int bit = io_pin % width;
    const char *conn = (port < HM2_LLIO_MAX_CONNECTORS && llio->ioport_connector_name[port])
                           ? llio->ioport_connector_name[port]
                           : "??";
    int pin;
    switch (width) {
    case 24: pin = 2 * bit + 1; break;
    case 17: pin = db25_order[bit]; break;
    default: pin = io_pin + 1; break;
    }
    snprintf(buf, len, "%s-%02d", conn, pin);
    return buf;
}

int hm2_llio_validate(const hm2_llio_t *llio, char *err, size_t len)
{
    if (!llio) {
        snprintf(err, len, "llio is NULL");
        return -EINVAL;
    }
    if (llio->name[0] == '\0') {
        snprintf(err, len, "llio has no name");
        return -EINVAL;
    }
    if (!llio->read || !llio->write) {
        snprintf(err, len, "llio %s lacks read or write", llio->name);
        return -EINVAL;
    }
    int q = !!llio->queue_read + !!llio->send_queued_reads + !!llio->queue_write +
            !!llio->send_queued_writes;
    if (q != 0 && q != 4) {
        snprintf(err, len, "llio %s has only some of the queued-access functions (need all four)",
                 llio->name);
        return -EINVAL;
    }
    if (!!llio->request_queued_reads != !!llio->receive_queued_reads) {
        snprintf(err, len,
                 "llio %s has only one of request_queued_reads/receive_queued_reads (need both "
                 "or none)",
                 llio->name);
        return -EINVAL;
    }
    if (llio->request_queued_reads && q == 0) {
        snprintf(err, len, "llio %s splits queued reads but has no queued access", llio->name);
        return -EINVAL;
    }
    if (!!llio->reset != !!llio->program_fpga) {
        snprintf(err, len, "llio %s has only one of reset/program_fpga (need both or none)",
                 llio->name);
        return -EINVAL;
    }
    if (llio->num_ioport_connectors < 0 || llio->num_ioport_connectors > HM2_LLIO_MAX_CONNECTORS) {
        snprintf(err, len, "llio %s: num_ioport_connectors %d out of range 0..%d", llio->name,
                 llio->num_ioport_connectors, HM2_LLIO_MAX_CONNECTORS);
        return -EINVAL;
    }
    if (llio->pins_per_connector <= 0 || llio->pins_per_connector > HM2_LLIO_MAX_IO_PINS) {
        snprintf(err, len, "llio %s: pins_per_connector %d out of range 1..%d", llio->name,
                 llio->pins_per_connector, HM2_LLIO_MAX_IO_PINS);
        return -EINVAL;
    }
    if (llio->num_leds < 0 || llio->num_leds > 32) {
        snprintf(err, len, "llio %s: num_leds %d out of range 0..32", llio->name, llio->num_leds);
        return -EINVAL;
    }
    return 0;
}
