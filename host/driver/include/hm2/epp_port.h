/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * epp_port.h - one interface to a PC-style parallel port in EPP mode, shared
 * by the Pluto-P drivers (pluto_servo, pluto_step) and the hostmot2 7i43
 * board driver (hm2_7i43).  See docs/epp_port.md.
 *
 * The model is the PC's register view of the port (spec/pluto.md §1,
 * spec/hostmot2.md §17.2):
 *
 *   base+0  SPP data register          (epp_spp_data_write)
 *   base+1  status register, bit 0 = EPP timeout (epp_status_read)
 *   base+2  control register           (epp_control_write)
 *   base+3  EPP address port: one access = one address cycle
 *   base+4  EPP data port: one access = one data cycle; with `wide` the
 *           backend may use 16/32-bit port I/O (2/4 cycles, LSB first)
 *   hi+2    ECR (extended control)     (epp_ecr_write)
 *
 * Operations are queued and executed in order by the backend.  Results of
 * reads (data bytes, status) are valid after epp_flush(), or at once for a
 * backend that executes immediately (ppdev, raw, gpiod: these run every
 * operation as it is queued).  A socket backend (the virtual board) sends a
 * whole queue as one request, so a servo period costs one round trip per
 * direction.  The caller keeps read buffers alive until the flush.
 *
 * Every function returns 0 or a negative errno (-EIO a backend I/O error,
 * -ENOMEM the queue cannot grow, -EINVAL bad argument).  An EPP timeout is
 * NOT an error return: like on a real port it only sets the timeout bit in
 * the status register, which the caller reads.  After a failed flush the
 * queue is empty and the read results of that flush are undefined.
 */
#ifndef HM2_EPP_PORT_H
#define HM2_EPP_PORT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Status register bit 0: EPP timeout. */
#define EPP_STATUS_TIMEOUT 0x01u

enum epp_op_kind {
    EPP_OP_ADDR_WRITE = 1, /* one address-write cycle: val */
    EPP_OP_ADDR_READ,      /* one address-read cycle -> buf[0] */
    EPP_OP_DATA_WRITE,     /* n data-write cycles from buf */
    EPP_OP_DATA_READ,      /* n data-read cycles into buf */
    EPP_OP_STATUS_READ,    /* status register -> buf[0] */
    EPP_OP_STATUS_WRITE,   /* status register <- val (clears the timeout) */
    EPP_OP_CONTROL_WRITE,  /* control register <- val */
    EPP_OP_SPP_DATA_WRITE, /* SPP data register <- val */
    EPP_OP_ECR_WRITE,      /* ECR <- val (ignored when the port has none) */
    EPP_OP_DELAY,          /* wait val nanoseconds (board time passes) */
};

/* One queued operation.  For DATA_WRITE buf points into the port's own
 * copy; for reads it is the caller's buffer.  width (1, 2 or 4) is the port
 * I/O size a direct backend uses for data cycles (n is a multiple of it). */
struct epp_op {
    uint8_t kind;
    uint8_t width;
    uint32_t n;
    uint32_t val;
    uint8_t *buf;
};

/* Cycle and access counters since open (or epp_counters_reset). */
struct epp_counters {
    uint64_t addr_cycles;    /* EPP address cycles (read + write) */
    uint64_t data_cycles;    /* EPP data cycles (read + write) */
    uint64_t data_reads;     /* of which reads */
    uint64_t reg_accesses;   /* status/control/SPP data/ECR accesses */
    uint64_t port_ios;       /* port instructions a direct backend needs
                                (an outl = 1 I/O, 4 cycles) */
    uint64_t flushes;        /* epp_flush calls that carried operations */
    uint64_t bus_ns;         /* simulated bus time, from the backend's cycle
                                model (see epp_port_set_timing) */
};

typedef struct epp_port epp_port_t;

/* What a backend provides.  execute() performs ops[0..n) in order, fills
 * the read buffers and returns 0, or -errno when the port itself failed
 * (not for an EPP timeout). */
struct epp_backend {
    const char *kind; /* "raw", "ppdev", "gpiod", "sim", "fake" */
    int batching;     /* 1: queue until flush; 0: execute each op at once */
    int (*execute)(epp_port_t *port, const struct epp_op *ops, size_t n);
    void (*close)(epp_port_t *port);
};

struct epp_port {
    char name[64];                   /* for messages: "raw:0x378", ... */
    const struct epp_backend *backend;
    void *priv;                      /* backend state */
    int wide;                        /* use 16/32-bit data port I/O */
    int has_ecr;                     /* ECR present (raw: ioaddr_hi != -1) */
    unsigned long base, base_hi;     /* raw I/O addresses (informational
                                        for other backends) */
    /* The queue. */
    struct epp_op *ops;
    size_t n_ops, cap_ops;
    uint8_t *pool; /* copies of write data */
    size_t n_pool, cap_pool;
    struct epp_counters count;
    /* Bus-time model for bus_ns: per address/data cycle and per register
     * access, in ns (defaults 1000 and 1000: a PC ISA-speed port). */
    uint32_t cycle_ns, reg_ns;
};

/* ---- opening ----------------------------------------------------------- */

/* How a driver names its port.  `spec` (the port= modparam) wins when it is
 * non-empty; otherwise the LinuxCNC ioaddr/ioaddr_hi pair selects the raw
 * backend (ioaddr < 16: parport number, addresses from
 * /proc/sys/dev/parport/parportN/base-addr).  Spec strings:
 *
 *   raw:0x378[,0x778]        raw port I/O (ioperm), optional ECR base
 *   ppdev:/dev/parport0      the kernel's ppdev (EPP mode)
 *   gpiod:CHIP:LINES[:OPTS]  bit-banged on 12 (13) GPIO lines, see docs
 *   sim:/path/to/socket      the virtual board
 *
 * 0 on success (port filled, caller frees with epp_port_close), -errno with
 * the reason in err otherwise. */
int epp_port_open(epp_port_t *port, const char *spec, long ioaddr, long ioaddr_hi, int wide,
                  char *err, size_t errlen);
void epp_port_close(epp_port_t *port);

/* The port kinds a spec may name ("kind:ARG"), one per backend file, in the
 * table epp_port_kinds (epp_kinds.c) that epp_port_open walks. */
struct epp_port_kind {
    const char *prefix; /* "raw", "ppdev", "gpiod", "sim" */
    const char *usage;  /* "raw:ADDR" (for the unknown-kind message) */
    /* arg: what follows "prefix:"; spec: the whole spec for messages */
    int (*open)(epp_port_t *port, const char *arg, const char *spec, int wide, char *err,
                size_t errlen);
};
extern const struct epp_port_kind epp_raw_kind, epp_ppdev_kind, epp_gpiod_kind, epp_sim_kind;
extern const struct epp_port_kind *const epp_port_kinds[];
extern const size_t epp_num_port_kinds;

/* For backends and tests: initialize a port around a backend. */
void epp_port_init(epp_port_t *port, const struct epp_backend *backend, void *priv,
                   const char *name, int wide);

/* ---- operations -------------------------------------------------------- */

int epp_addr_write(epp_port_t *port, uint8_t addr);
int epp_addr_read(epp_port_t *port, uint8_t *out);
/* n data cycles; wide ports use 4-/2-byte port I/O when n allows */
int epp_data_write(epp_port_t *port, const void *buf, size_t n);
int epp_data_read(epp_port_t *port, void *buf, size_t n);
/* Byte-wide data cycles regardless of `wide` (CPLD configuration). */
int epp_data_write8(epp_port_t *port, const void *buf, size_t n);
int epp_status_read(epp_port_t *port, uint8_t *out);
int epp_status_write(epp_port_t *port, uint8_t val);
int epp_control_write(epp_port_t *port, uint8_t val);
int epp_spp_data_write(epp_port_t *port, uint8_t val);
int epp_ecr_write(epp_port_t *port, uint8_t val);
int epp_delay(epp_port_t *port, uint32_t ns);

/* Execute everything queued.  0 or -errno (queue emptied either way). */
int epp_flush(epp_port_t *port);
/* Drop the queue without executing it. */
void epp_discard(epp_port_t *port);

/* Flush, read status: 1 when the timeout bit is set, 0 when not, -errno. */
int epp_timeout(epp_port_t *port);
/* The Pluto driver's clear (pluto_clear_error_register): r = status;
 * status <- r | 1; status <- r & ~1.  Queued; no flush. */
int epp_clear_timeout_pluto(epp_port_t *port);
/* The hm2_7i43 clear: if the timeout bit is set, read status twice, write
 * (status | 1) then (status & ~1), read again.  Flushes.  0 when clear
 * afterwards, 1 when it is still set, -errno. */
int epp_clear_timeout_hm2(epp_port_t *port);

void epp_counters_reset(epp_port_t *port);
void epp_port_set_timing(epp_port_t *port, uint32_t cycle_ns, uint32_t reg_ns);

/* ---- backends (for tests: each takes an injectable lower layer) -------- */

/* Raw port I/O: the seven port instructions, real ones use sys/io.h. */
struct epp_raw_io {
    int (*ioperm)(void *ctx, unsigned long from, unsigned long num, int on);
    uint8_t (*inb)(void *ctx, unsigned long port);
    uint16_t (*inw)(void *ctx, unsigned long port);
    uint32_t (*inl)(void *ctx, unsigned long port);
    void (*outb)(void *ctx, uint8_t v, unsigned long port);
    void (*outw)(void *ctx, uint16_t v, unsigned long port);
    void (*outl)(void *ctx, uint32_t v, unsigned long port);
    void *ctx;
};
extern const struct epp_raw_io epp_raw_sys_io;
/* base_hi: ECR base, or -1 for none (0 is NOT resolved here: callers pass
 * ioaddr + 0x400 themselves, see epp_port_open). */
int epp_raw_open(epp_port_t *port, const struct epp_raw_io *io, unsigned long base, long base_hi,
                 int wide, char *err, size_t errlen);

/* ppdev: the system calls the backend makes. */
struct epp_ppdev_sys {
    int (*open)(void *ctx, const char *path, int flags);
    int (*close)(void *ctx, int fd);
    int (*ioctl)(void *ctx, int fd, unsigned long req, void *arg);
    long (*read)(void *ctx, int fd, void *buf, size_t n);
    long (*write)(void *ctx, int fd, const void *buf, size_t n);
    void *ctx;
};
extern const struct epp_ppdev_sys epp_ppdev_sys_libc;
int epp_ppdev_open(epp_port_t *port, const struct epp_ppdev_sys *sys, const char *path, int wide,
                   char *err, size_t errlen);

/* gpiod: a line layer.  Lines are numbered by role (below); the real layer
 * (epp_gpiod_lines_open) maps them to line offsets of one chip with the
 * libgpiod 1.6 API. */
enum epp_gpio_role {
    EPP_GPIO_D0 = 0, /* D0..D7 = 0..7, bidirectional */
    EPP_GPIO_NWRITE = 8,   /* LPT pin 1  (nStrobe)   output */
    EPP_GPIO_NDATASTR = 9, /* LPT pin 14 (nAutoFd)   output */
    EPP_GPIO_NADDRSTR = 10, /* LPT pin 17 (nSelectIn) output */
    EPP_GPIO_NWAIT = 11,   /* LPT pin 11 (Busy)      input */
    EPP_GPIO_NINIT = 12,   /* LPT pin 16 (nInit)     output, optional */
    EPP_GPIO_NLINES = 13
};
struct epp_gpio_lines {
    /* Data bus direction: 1 = the host drives D0..D7. */
    int (*data_dir)(void *ctx, int out);
    /* Set the 8 data lines (only while driving). */
    int (*data_set)(void *ctx, uint8_t v);
    int (*data_get)(void *ctx, uint8_t *v);
    int (*set)(void *ctx, int role, int level);
    int (*get)(void *ctx, int role, int *level);
    /* Monotonic time in ns (the timeout clock; a fake may make its own). */
    uint64_t (*now_ns)(void *ctx);
    void (*close)(void *ctx);
    void *ctx;
    int has_ninit;
};
/* Parse "CHIP:LINES[:OPTS]" and request the lines from the kernel. */
int epp_gpiod_lines_open(struct epp_gpio_lines *lines, const char *spec, uint32_t *timeout_ns,
                         char *err, size_t errlen);
/* timeout_ns: how long a cycle waits for nWait (a PC port: ~10 us). */
int epp_gpiod_open(epp_port_t *port, const struct epp_gpio_lines *lines, uint32_t timeout_ns,
                   const char *name, char *err, size_t errlen);

/* The virtual board (host/driver/backends/sim client library). */
int epp_sim_open(epp_port_t *port, const char *socket_path, int wide, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* HM2_EPP_PORT_H */
