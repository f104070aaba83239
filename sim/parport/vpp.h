/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * vpp.h - the virtual PC parallel port (see docs/vparport.md).
 *
 * A virtual port is a small file in shared memory (/dev/shm/vparport.NAME,
 * or any path) holding what a real port has: the registers the host
 * programs (data, control, ECR) and the 17 signal pins of the DB-25.  The
 * host side (hal_parport's sim: backend) does port I/O through
 * vpp_inb/vpp_outb exactly as it would with inb/outb on a real port; the
 * outside world (the vparport tool, a test) drives and reads pins.
 *
 * Registers (offsets from the port's base address):
 *
 *   +0      data: bits 0-7 = pins 2-9.  Reads give the pin levels.
 *   +1      status (read only): bit 7 = NOT pin 11 (Busy, inverted by the
 *           port), bit 6 = pin 10, bit 5 = pin 12, bit 4 = pin 13,
 *           bit 3 = pin 15; bits 2-1 read 1, bit 0 (EPP timeout) reads 0.
 *   +2      control: bit 0 = NOT pin 1, bit 1 = NOT pin 14, bit 2 = pin 16,
 *           bit 3 = NOT pin 17 (the port inverts bits 0, 1 and 3), bit 4
 *           IRQ enable, bit 5 data direction (1 = the port's data drivers
 *           are off: pins 2-9 become inputs).  Reads give bits 0-3 from the
 *           pin levels, bits 4-5 as written, bits 6-7 read 1.
 *   +0x402  ECR (only a port created with an ECR): bits 7-5 mode (000 SPP,
 *           001 PS/2 byte mode, 010 fast centronics, 011 ECP, 100 EPP,
 *           110 test, 111 config), bits 4-2 as written, bit 1 (FIFO full)
 *           reads 0, bit 0 (FIFO empty) reads 1.  Power-on value 0x15.  On
 *           a port with an ECR the direction bit works only in the modes
 *           other than 000 (SPP), as on real ECP chips.  A port without an
 *           ECR reads 0xFF there and ignores writes (nothing on the bus).
 *
 * Pins: a mask with bit n = DB-25 pin n (1..17).  Electrical model:
 *   data pins 2-9     push-pull outputs while the port drives them; with
 *                     the drivers off they follow what the outside drives,
 *                     pulled up (1) when nobody drives.
 *   control 1,14,16,17 open-collector (default: 1 unless the port or the
 *                     outside pulls low) or push-pull (the port's level).
 *   status 10-13,15   inputs, pulled up (1) when nobody drives.
 * Where the port drives push-pull against an outside driver at the other
 * level, the port's level wins and the contention counter goes up.
 *
 * Log: every host register write that changes a pin level appends
 * {time, pin levels}; time is the host's (HAL's rtapi_get_time(), so the
 * simulated clock gives exact, reproducible times).
 *
 * All fields are read and written with atomic operations: the host and
 * any number of vparport invocations may use a port at the same time.
 */
#ifndef VPP_H
#define VPP_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VPP_MAGIC 0x31505056u /* "VPP1" */
#define VPP_VERSION 1u
#define VPP_LOG_LEN 65536u
#define VPP_ECR_OFFSET 0x402u
#define VPP_ECR_RESET 0x15u
#define VPP_PIN(n) (1u << (n))
#define VPP_DATA_PINS 0x3fcu                                   /* pins 2-9 */
#define VPP_STATUS_PINS (VPP_PIN(10) | VPP_PIN(11) | VPP_PIN(12) | VPP_PIN(13) | VPP_PIN(15))
#define VPP_CONTROL_PINS (VPP_PIN(1) | VPP_PIN(14) | VPP_PIN(16) | VPP_PIN(17))
#define VPP_ALL_PINS (VPP_DATA_PINS | VPP_STATUS_PINS | VPP_CONTROL_PINS)

/* Creation options. */
#define VPP_OPT_ECR 0x1u          /* the port has an ECR at +0x402 */
#define VPP_OPT_CONTROL_PP 0x2u   /* control pins push-pull (default: open collector) */
#define VPP_OPT_NO_BIDIR 0x4u     /* an old SPP-only port: the direction bit does nothing */

/* Register indices for the counters. */
enum { VPP_REG_DATA, VPP_REG_STATUS, VPP_REG_CONTROL, VPP_REG_ECR, VPP_REG_OTHER, VPP_NREGS };

struct vpp_log_entry {
    uint64_t t_ns;
    uint32_t pins;
    uint32_t seq; /* low 32 bits of the entry number + 1 once written */
};

/* The shared file.  Only the functions below touch it. */
struct vpp_state {
    uint32_t magic, version, size, options;
    int32_t owner_pid;     /* the host that claimed the port, 0 = free */
    uint32_t data_latch;   /* data register as last written */
    uint32_t control_latch;/* control register bits 0-5 as last written */
    uint32_t ecr;          /* ECR bits 7-2 as last written */
    uint32_t ext_drive;    /* pins the outside drives */
    uint32_t ext_level;    /* and at which level */
    uint32_t last_pins;    /* pin levels after the last host write */
    uint32_t pad;
    uint64_t last_t_ns;    /* host time of the last register access */
    uint64_t reads[VPP_NREGS], writes[VPP_NREGS];
    uint64_t contention;   /* host writes that drove against the outside */
    uint64_t log_head;     /* entries appended since creation */
    uint64_t log_base;     /* entries before this one were cleared */
    struct vpp_log_entry log[VPP_LOG_LEN];
};

/* ---- the file ------------------------------------------------------------ */

/* NAME without '/' is /dev/shm/vparport.NAME; with '/' it is a path. */
int vpp_path(const char *name, char *path, size_t len);
/* Create (fails with -EEXIST unless replace) with options VPP_OPT_*. */
int vpp_create(const char *name, unsigned options, int replace, char *err, size_t errlen);
int vpp_remove(const char *name, char *err, size_t errlen);
/* Map an existing port.  -ENOENT when there is none, -EINVAL when the file
 * is not a virtual port. */
int vpp_open(const char *name, struct vpp_state **st, char *err, size_t errlen);
void vpp_close(struct vpp_state *st);

/* Claim for a host (-EBUSY with the owner's pid in err when another live
 * process holds it; a dead owner's claim is taken over). */
int vpp_claim(struct vpp_state *st, int pid, const char *name, char *err, size_t errlen);
void vpp_release(struct vpp_state *st, int pid);

/* ---- the host side: port I/O at an offset from the base ------------------ */

uint8_t vpp_inb(struct vpp_state *st, unsigned offset, uint64_t t_ns);
void vpp_outb(struct vpp_state *st, unsigned offset, uint8_t v, uint64_t t_ns);

/* ---- the outside --------------------------------------------------------- */

/* Pin levels now (bit n = pin n). */
uint32_t vpp_pins(const struct vpp_state *st);
/* Pins the port itself drives now (its outputs; open-collector control
 * pins only while pulled low), and at which levels (*level may be NULL). */
uint32_t vpp_port_drive(const struct vpp_state *st, uint32_t *level);
/* Drive pin (1..17) at level 0/1, or release it (level < 0).  -EINVAL for
 * a pin that is not a signal pin. */
int vpp_drive(struct vpp_state *st, int pin, int level);
/* Entries [from, head) still in the log are copied to out (at most max);
 * returns how many, *first = the number of the first one copied. */
size_t vpp_log_read(const struct vpp_state *st, uint64_t from, struct vpp_log_entry *out,
                    size_t max, uint64_t *first);
uint64_t vpp_log_head(const struct vpp_state *st);
/* Forget the entries logged so far. */
void vpp_log_clear(struct vpp_state *st);
void vpp_counters_reset(struct vpp_state *st);

#ifdef __cplusplus
}
#endif

#endif /* VPP_H */
