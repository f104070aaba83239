/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_common.h - what pluto_servo and pluto_step share (spec/pluto.md
 * §1, §4.3, §8, §9): count extension, the FPGA upload over the parallel
 * port, the timeout check/clear, the EPP access helpers.  No HAL calls
 * here, so the unit tests link it directly.
 */
#ifndef PLUTO_COMMON_H
#define PLUTO_COMMON_H

#include <stddef.h>
#include <stdint.h>

#include "hm2/epp_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The LinuxCNC upload sends this many bytes of the .rbf (the shipped files
 * have 19897; the last two are never sent). */
#define PLUTO_UPLOAD_BYTES 19895u
/* Largest firmware file we accept (an EP1K10 .rbf is ~20 KB). */
#define PLUTO_FIRMWARE_MAX (1u << 20)

/* Extend a counter of `bits` bits that wraps in hardware to 64 bits, given
 * the last extended value (spec §4.3 extend()). */
int64_t pluto_extend(int64_t old, uint32_t newlow, int bits);

/* Little-endian helpers for the EPP byte streams. */
static inline uint32_t pluto_le32(const uint8_t *b)
{
    return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}
static inline void pluto_put16(uint8_t *b, uint16_t v)
{
    b[0] = (uint8_t)v;
    b[1] = (uint8_t)(v >> 8);
}

/* Messages: a function the module supplies (rtapi_print_msg in the real
 * module, a capture in the tests).  level: 1 = error, 3 = info. */
typedef void (*pluto_log_fn)(void *ctx, int level, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
struct pluto_log {
    pluto_log_fn fn;
    void *ctx;
};
#define PLUTO_ERR 1
#define PLUTO_INFO 3

/* The servo-period transfers both drivers share (spec §4.1, §6.1).  A
 * failure of the port itself (socket gone, ...) counts as a communication
 * error like an EPP timeout and is logged with `board` ("pluto-servo").
 * *comm_error is the driver's communication-error parameter.
 *
 * Write: address 0, then the data writes of w (sizes[k] bytes each, in
 * order), one flush. */
void pluto_write_transfer(epp_port_t *p, const uint8_t *w, const uint8_t *sizes, int n,
                          volatile uint32_t *comm_error, const struct pluto_log *log,
                          const char *board);
/* Read: address 0, 4 bytes, the status register (timeout bit: error, the
 * timeout cleared), 16 more bytes into rbuf[20].  On a batching port the
 * 16 bytes are queued before the status is known (one flush).  Returns 1
 * when rbuf holds this period's data, 0 when there is a communication
 * error (now or from before: the outputs keep their values). */
int pluto_read_transfer(epp_port_t *p, uint8_t rbuf[20], uint8_t *status,
                        volatile uint32_t *comm_error, const struct pluto_log *log,
                        const char *board);

/* Send a firmware image over the port exactly as spec §8 (steps 1-6) says:
 * control 0x04, ECR 0x00, nCONFIG pulse (control 0x00 x4, 0x04 x20), then
 * for every bit LSB first: data <- 0xFF/0x00, control <- 0x04, 0x05, 0x04;
 * then ECR 0x80.  At most PLUTO_UPLOAD_BYTES bytes are sent.  Flushes. */
int pluto_upload(epp_port_t *port, const uint8_t *image, size_t len, const struct pluto_log *log);

/* Step 7: clear timeout, EPP address 0, one data read, check the timeout
 * bit.  0 when the board answered, -EIO (after printing `Failed to
 * communicate with <board> board after programming firmware.`). */
int pluto_probe(epp_port_t *port, const char *board, const struct pluto_log *log);

/* Load the firmware file: `name` is looked up on the firmware search path
 * (relative name) or used as is (absolute path).  Checks that it is not
 * empty and not larger than PLUTO_FIRMWARE_MAX.  malloc'd buffer. */
int pluto_read_firmware(const char *name, uint8_t **buf, size_t *len, char *path_out,
                        size_t path_len, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* PLUTO_COMMON_H */
