/* SPDX-License-Identifier: GPL-2.0-or-later */
/* jtag_usb.c - FTDI MPSSE cable over libusb (hm2/jtag_usb.h). */
#define _POSIX_C_SOURCE 200809L
#include "hm2/jtag_usb.h"

#include <errno.h>
#include <libusb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* FTDI vendor requests (bmRequestType 0x40), channel A = index 1. */
#define FTDI_OUT 0x40
#define SIO_RESET 0x00
#define SIO_SET_LATENCY 0x09
#define SIO_SET_BITMODE 0x0B
#define SIO_RESET_SIO 0
#define SIO_PURGE_RX 1
#define SIO_PURGE_TX 2
#define BITMODE_RESET 0x0000
#define BITMODE_MPSSE 0x0200
#define EP_OUT 0x02
#define EP_IN 0x81
#define CHANNEL_A 1

static int errno_of(int usb)
{
    switch (usb) {
    case LIBUSB_ERROR_ACCESS: return -EACCES;
    case LIBUSB_ERROR_NO_DEVICE: return -ENODEV;
    case LIBUSB_ERROR_NOT_FOUND: return -ENODEV;
    case LIBUSB_ERROR_BUSY: return -EBUSY;
    case LIBUSB_ERROR_TIMEOUT: return -ETIMEDOUT;
    case LIBUSB_ERROR_NO_MEM: return -ENOMEM;
    default: return -EIO;
    }
}

static int usb_fail(struct jtag_usb *u, int usb, const char *what)
{
    snprintf(u->err, sizeof(u->err), "%s: %s (%s)", what, libusb_strerror((enum libusb_error)usb),
             libusb_error_name(usb));
    return errno_of(usb);
}

int jtag_usb_parse(const char *spec, uint16_t *vid, uint16_t *pid, char *serial, size_t slen,
                   char *err, size_t errlen)
{
    *vid = 0x0403;
    *pid = 0x6010;
    serial[0] = 0;
    if (strcmp(spec, "ftdi") == 0)
        return 0;
    unsigned v, p;
    int used = 0;
    if (strncmp(spec, "ftdi:", 5) != 0 || sscanf(spec + 5, "%4x:%4x%n", &v, &p, &used) != 2 ||
        (spec[5 + used] != 0 && spec[5 + used] != ':')) {
        snprintf(err, errlen, "bad JTAG cable '%s': want ftdi, ftdi:VID:PID or "
                              "ftdi:VID:PID:SERIAL (VID/PID in hex, e.g. ftdi:0403:6014)", spec);
        return -EINVAL;
    }
    *vid = (uint16_t)v;
    *pid = (uint16_t)p;
    if (spec[5 + used] == ':')
        snprintf(serial, slen, "%s", spec + 6 + used);
    return 0;
}

static int serial_matches(libusb_device_handle *h, const struct libusb_device_descriptor *d,
                          const char *want)
{
    if (!want[0])
        return 1;
    unsigned char s[64];
    if (!d->iSerialNumber ||
        libusb_get_string_descriptor_ascii(h, d->iSerialNumber, s, sizeof(s)) < 0)
        return 0;
    return strcmp((const char *)s, want) == 0;
}

static int find(struct jtag_usb *u)
{
    libusb_device **list = NULL;
    ssize_t n = libusb_get_device_list(u->ctx, &list);
    if (n < 0)
        return usb_fail(u, (int)n, "listing USB devices");
    int r = -ENODEV, seen = 0, denied = 0;
    for (ssize_t i = 0; i < n && !u->handle; i++) {
        struct libusb_device_descriptor d;
        if (libusb_get_device_descriptor(list[i], &d) || d.idVendor != u->vid ||
            d.idProduct != u->pid)
            continue;
        seen++;
        libusb_device_handle *h = NULL;
        int e = libusb_open(list[i], &h);
        if (e) {
            denied += e == LIBUSB_ERROR_ACCESS;
            r = usb_fail(u, e, "opening the cable");
            continue;
        }
        if (serial_matches(h, &d, u->serial))
            u->handle = h;
        else
            libusb_close(h);
    }
    libusb_free_device_list(list, 1);
    if (u->handle)
        return 0;
    if (denied)
        snprintf(u->err, sizeof(u->err),
                 "permission denied opening the FTDI cable %04x:%04x: add a udev rule (e.g. "
                 "SUBSYSTEM==\"usb\", ATTR{idVendor}==\"%04x\", ATTR{idProduct}==\"%04x\", "
                 "MODE=\"0660\", GROUP=\"plugdev\") or run as root",
                 u->vid, u->pid, u->vid, u->pid);
    else if (!seen || u->serial[0])
        snprintf(u->err, sizeof(u->err), "no FTDI cable %04x:%04x%s%s found on USB (%zd devices)",
                 u->vid, u->pid, u->serial[0] ? " with serial " : "", u->serial, n);
    return denied ? -EACCES : r;
}

static int ctrl(struct jtag_usb *u, uint8_t req, uint16_t value, const char *what)
{
    int e = libusb_control_transfer(u->handle, FTDI_OUT, req, value, CHANNEL_A, NULL, 0,
                                    u->timeout_ms);
    return e < 0 ? usb_fail(u, e, what) : 0;
}

int jtag_usb_open(struct jtag_usb *u, const char *spec)
{
    memset(u, 0, sizeof(*u));
    u->timeout_ms = 1000;
    int r = jtag_usb_parse(spec, &u->vid, &u->pid, u->serial, sizeof(u->serial), u->err,
                           sizeof(u->err));
    if (r)
        return r;
    libusb_context *ctx = NULL;
    int e = libusb_init(&ctx);
    if (e)
        return usb_fail(u, e, "cannot initialise libusb");
    u->ctx = ctx;
    if ((r = find(u)))
        goto fail;
    libusb_set_auto_detach_kernel_driver(u->handle, 1); /* ftdi_sio */
    e = libusb_claim_interface(u->handle, 0);
    if (e) {
        r = usb_fail(u, e, "claiming the cable's channel A (another program uses it?)");
        goto fail;
    }
    u->claimed = 1;
    if ((r = ctrl(u, SIO_RESET, SIO_RESET_SIO, "resetting the FTDI chip")) ||
        (r = ctrl(u, SIO_RESET, SIO_PURGE_RX, "purging the receive buffer")) ||
        (r = ctrl(u, SIO_RESET, SIO_PURGE_TX, "purging the transmit buffer")) ||
        (r = ctrl(u, SIO_SET_LATENCY, 2, "setting the latency timer")) ||
        (r = ctrl(u, SIO_SET_BITMODE, BITMODE_RESET, "resetting the bit mode")) ||
        (r = ctrl(u, SIO_SET_BITMODE, BITMODE_MPSSE | 0x0B, "entering MPSSE mode")))
        goto fail;
    return 0;
fail:
    {
        char keep[sizeof(u->err)];
        memcpy(keep, u->err, sizeof(keep));
        jtag_usb_close(u);
        memcpy(u->err, keep, sizeof(keep));
    }
    return r;
}

void jtag_usb_close(struct jtag_usb *u)
{
    if (u->handle) {
        if (u->claimed) {
            ctrl(u, SIO_SET_BITMODE, BITMODE_RESET, "leaving MPSSE mode");
            libusb_release_interface(u->handle, 0);
        }
        libusb_close(u->handle);
    }
    if (u->ctx)
        libusb_exit(u->ctx);
    u->handle = NULL;
    u->ctx = NULL;
    u->claimed = 0;
}

static int usb_write(void *ctx, const uint8_t *buf, size_t n)
{
    struct jtag_usb *u = ctx;
    while (n) {
        int done = 0, chunk = n > 4096 ? 4096 : (int)n;
        int e = libusb_bulk_transfer(u->handle, EP_OUT, (unsigned char *)buf, chunk, &done,
                                     u->timeout_ms);
        if (e)
            return usb_fail(u, e, "USB write to the cable");
        buf += done;
        n -= (size_t)done;
    }
    return 0;
}

/* Every USB packet from the chip starts with two modem-status bytes. */
static int usb_read(void *ctx, uint8_t *buf, size_t n)
{
    struct jtag_usb *u = ctx;
    int empty = 0;
    while (n) {
        int got = 0;
        int e = libusb_bulk_transfer(u->handle, EP_IN, u->rx, sizeof(u->rx), &got, u->timeout_ms);
        if (e)
            return usb_fail(u, e, "USB read from the cable");
        if (got <= 2) {
            if (++empty > 1000) {
                snprintf(u->err, sizeof(u->err), "the cable sent no TDO data (%zu bytes missing)",
                         n);
                return -ETIMEDOUT;
            }
            continue;
        }
        size_t k = (size_t)got - 2 < n ? (size_t)got - 2 : n;
        memcpy(buf, u->rx + 2, k);
        buf += k;
        n -= k;
    }
    return 0;
}

static const char *usb_error(void *ctx)
{
    return ((struct jtag_usb *)ctx)->err;
}

struct mpsse_transport jtag_usb_transport(struct jtag_usb *u)
{
    return (struct mpsse_transport){usb_write, usb_read, usb_error, u};
}
