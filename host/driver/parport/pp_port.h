/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pp_port.h - a PC parallel port in SPP/bidirectional use, as hal_parport
 * sees it: the three registers of the port (docs/hal_parport.md).
 *
 *   data     bits 0-7 = pins 2-9
 *   status   bit 7 = NOT pin 11, bit 6 = pin 10, bit 5 = pin 12,
 *            bit 4 = pin 13, bit 3 = pin 15
 *   control  bit 0 = NOT pin 1, bit 1 = NOT pin 14, bit 2 = pin 16,
 *            bit 3 = NOT pin 17, bit 5 = data direction (1 = input)
 *
 * Backends: raw port I/O (ioperm + inb/outb, optional ECR), the kernel's
 * ppdev, GPIO lines through libgpiod, and the virtual port (raw port I/O
 * against vparport's model, so the register code under test is the raw
 * backend's).  Register access returns 0 or -errno (a ppdev ioctl or a GPIO
 * request that failed); the raw and virtual ports cannot fail.
 */
#ifndef PP_PORT_H
#define PP_PORT_H

#include <stddef.h>
#include <stdint.h>

#include "hm2/epp_port.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How the port is used (the cfg type word). */
enum pp_mode { PP_MODE_OUT, PP_MODE_IN, PP_MODE_EPP, PP_MODE_X };

#define PP_CTRL_DIR 0x20u
/* Control register value that releases pins 1, 14, 16, 17 (all high):
 * the x-mode setting, where they are open-collector inputs. */
#define PP_CTRL_RELEASED 0x04u

struct pp_port;

struct pp_ops {
    /* Called at the start of every realtime function on a port (raw: I/O
     * permission for the calling thread).  0 or -errno. */
    int (*begin)(struct pp_port *p);
    int (*read_data)(struct pp_port *p, uint8_t *v);
    int (*write_data)(struct pp_port *p, uint8_t v);
    int (*read_status)(struct pp_port *p, uint8_t *v);
    int (*read_control)(struct pp_port *p, uint8_t *v);
    int (*write_control)(struct pp_port *p, uint8_t v);
    void (*close)(struct pp_port *p);
};

struct pp_port {
    char name[96];           /* for messages: "0x378", "ppdev /dev/parport0", ... */
    const char *kind;        /* "raw", "ppdev", "gpiod", "sim" */
    const struct pp_ops *ops;
    void *priv;
    enum pp_mode mode;
    /* Host time before which nothing written may be stamped (the virtual
     * port's log under HAL's simulated clock, where functions take no
     * time: reset's wait for reset-time).  0 = none. */
    long long stamp_floor;
    /* Host time source for the virtual port's log (rtapi_get_time). */
    long long (*clock)(void);
    /* What opening decided that the user may want to know (info message). */
    char note[200];
};

/* ---- opening (pp_open.c) ------------------------------------------------ */

/* Everything the system layers need, injectable for the unit tests. */
struct pp_sys {
    const struct epp_raw_io *io;       /* port instructions */
    const struct epp_ppdev_sys *ppdev; /* ppdev system calls */
    /* read /proc/sys/dev/parport/parportN/base-addr: first address, or
     * -ENOENT when Linux has no parport N */
    long (*linux_base)(void *ctx, int index);
    /* does /dev/parportN exist */
    int (*have_dev)(void *ctx, int index);
    void *ctx;
};
extern const struct pp_sys pp_sys_linux;

/* Open the port named by one cfg address (see pp_cfg.h for the forms) in
 * `mode`.  Registers are set up for the mode (data direction, ECR, x mode's
 * released control pins); nothing else is written.  0, or -errno with the
 * reason in err. */
struct pp_cfg_port;
int pp_open(struct pp_port *p, const struct pp_cfg_port *cfg, const struct pp_sys *sys,
            long long (*clock)(void), char *err, size_t errlen);
void pp_close(struct pp_port *p);

/* ---- backends ----------------------------------------------------------- */

/* Raw port I/O at base (data, status, control at base+0..2) with the ECR at
 * hi+2; hi < 0: no ECR; hi == 0: base+0x400, probed (an ECR is only used
 * when one answers there).  claim_fd >= 0: a ppdev descriptor holding
 * Linux's claim on the port while raw I/O runs (closed with the port). */
int pp_raw_open(struct pp_port *p, const struct epp_raw_io *io, const struct epp_ppdev_sys *sys,
                unsigned long base, long hi, int claim_fd, enum pp_mode mode, char *err,
                size_t errlen);
/* ppdev: PPRDATA/PPWDATA/PPRSTATUS/PPWCONTROL/PPDATADIR on a claimed port.
 * x mode is refused (Linux reads the control register back from a
 * software copy, so control pins cannot be inputs). */
int pp_ppdev_open(struct pp_port *p, const struct epp_ppdev_sys *sys, const char *path,
                  enum pp_mode mode, char *err, size_t errlen);
/* Claim /dev/parportN exclusively for raw I/O: the descriptor, or -errno. */
int pp_ppdev_claim(const struct epp_ppdev_sys *sys, const char *path, char *err, size_t errlen);

/* GPIO: one line per DB-25 pin 1..17.  The line layer (real: libgpiod). */
struct pp_gpio_lines {
    /* Request line `pin` (1..17): out=1 output at level, 0 input; od=1 an
     * open-drain output.  0 or -errno. */
    int (*config)(void *ctx, int pin, int out, int od, int level);
    int (*set)(void *ctx, int pin, int level);
    int (*get)(void *ctx, int pin, int *level);
    int (*has)(void *ctx, int pin); /* is the pin wired to a line */
    void (*close)(void *ctx);
    void *ctx;
};
/* Parse "CHIP:lines=P1/P2/.../P17" ('-' = not wired) and request nothing
 * yet (pp_gpiod_open configures the lines for the mode). */
int pp_gpiod_lines_open(struct pp_gpio_lines *l, const char *spec, char *err, size_t errlen);
int pp_gpiod_open(struct pp_port *p, const struct pp_gpio_lines *l, const char *name,
                  enum pp_mode mode, char *err, size_t errlen);

/* The virtual port NAME (vparport), through the raw backend. */
int pp_sim_open(struct pp_port *p, const char *vname, long hi, enum pp_mode mode, char *err,
                size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* PP_PORT_H */
