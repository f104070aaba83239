/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * jtag_mpsse.h - the JTAG cable of FTDI FT2232H/FT232H chips in MPSSE mode
 * (FTDI AN_108 command set): TCK = ADBUS0, TDI = ADBUS1, TDO = ADBUS2,
 * TMS = ADBUS3, as the Xilinx-compatible FTDI cables wire them.
 *
 * The engine turns jtag_cable clock() calls into MPSSE commands and sends
 * them through a transport: libusb to a real chip (jtag_usb.h), or anything
 * that speaks the same byte stream (the tests' MPSSE decoder).  Commands
 * are buffered; reads are answered when the buffer is sent (flush, or when
 * it is full), with a Send Immediate (0x87) at the end.
 */
#ifndef HM2_JTAG_MPSSE_H
#define HM2_JTAG_MPSSE_H

#include <stddef.h>
#include <stdint.h>

#include "hm2/jtag.h"

#ifdef __cplusplus
extern "C" {
#endif

struct mpsse_transport {
    /* Write all n bytes / read exactly n bytes (the transport's own timeout:
     * a cable that vanished is an error, not a hang).  0 or -errno. */
    int (*write)(void *ctx, const uint8_t *buf, size_t n);
    int (*read)(void *ctx, uint8_t *buf, size_t n);
    const char *(*error)(void *ctx);
    void *ctx;
};

struct mpsse_read {
    uint8_t *dst;   /* TDO vector */
    size_t bit;     /* first bit in dst */
    uint32_t nbits; /* bits this reply holds */
    uint8_t kind;   /* 0 whole bytes, 1 bits (top of a byte) */
};

struct mpsse {
    struct mpsse_transport t;
    uint8_t *cmd;
    size_t ncmd, cap;
    struct mpsse_read *reads;
    size_t nreads, capreads;
    size_t reply_bytes; /* expected from the queued commands */
    int tms_pin;        /* level TMS is left at */
    char err[256];
    /* statistics: for bytes per bit and commands per byte */
    uint64_t bytes_out, commands, tck;
};

/* Set up the chip (no clock divide-by-5, no adaptive clocking, no 3-phase,
 * pins, loopback off) for a TCK of `hz` (60 MHz / (2 * (1 + divisor))). */
int mpsse_open(struct mpsse *m, const struct mpsse_transport *t, uint32_t hz);
void mpsse_close(struct mpsse *m);
/* The jtag_cable of this engine. */
struct jtag_cable mpsse_cable(struct mpsse *m);

#ifdef __cplusplus
}
#endif

#endif /* HM2_JTAG_MPSSE_H */
