/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * jtag_usb.h - the USB side of an FTDI MPSSE JTAG cable, over libusb: find
 * the chip by VID:PID (and serial), claim channel A, reset it, put it in
 * MPSSE mode, and move the command/reply bytes (mpsse_transport).
 *
 * Cable spec: "ftdi" (0403:6010, an FT2232H), "ftdi:VID:PID" (hex, e.g.
 * 0403:6014 for an FT232H) or "ftdi:VID:PID:SERIAL".
 */
#ifndef HM2_JTAG_USB_H
#define HM2_JTAG_USB_H

#include <stdint.h>

#include "hm2/jtag_mpsse.h"

#ifdef __cplusplus
extern "C" {
#endif

struct jtag_usb {
    void *ctx;    /* libusb_context */
    void *handle; /* libusb_device_handle */
    int claimed;
    uint16_t vid, pid;
    char serial[64];
    unsigned timeout_ms;
    uint8_t rx[512];
    char err[256];
};

/* Parse a cable spec (see above): 0 or -EINVAL with the reason in err. */
int jtag_usb_parse(const char *spec, uint16_t *vid, uint16_t *pid, char *serial, size_t slen,
                   char *err, size_t errlen);
/* Open the cable: 0, or -errno with what to do in u->err (no such device,
 * permission denied, busy). */
int jtag_usb_open(struct jtag_usb *u, const char *spec);
void jtag_usb_close(struct jtag_usb *u);
/* The transport for mpsse_open(). */
struct mpsse_transport jtag_usb_transport(struct jtag_usb *u);

#ifdef __cplusplus
}
#endif

#endif /* HM2_JTAG_USB_H */
