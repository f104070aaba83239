/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * vboard/proto.h - the virtual board's wire protocol (Unix-domain stream
 * socket).  Shared by the board (sim/verilator, C++) and its clients (the
 * host driver's sim backends in C, tools, the Python test client).
 * docs/vboard-protocol.md is the prose version of this file.
 *
 * Framing.  A client sends a request, the board answers with exactly one
 * reply, in order.  Both start with a fixed 24-byte little-endian header
 * followed by `length` payload bytes.  Several clients may be connected at
 * once (the driver and a test's probe client); the board serves each request
 * whole, so requests of different clients never interleave.
 *
 * Time.  Every request carries the client's time in ns (host_time_ns).  In
 * lockstep mode (default) the board first runs its FPGA clocks up to that
 * time, then executes the request; host_time_ns == 0 means "do not advance"
 * (probe clients use it).  The first non-zero time seen on a connection sets
 * that connection's epoch so that board time continues where it was
 * (board_time = host_time - epoch; it never goes backwards: an earlier time
 * is executed at the current board time).  In free-running mode the board
 * advances with the wall clock, also between requests, and host times are
 * ignored.  Every reply carries the board time after the request.
 *
 * Errors.  A reply with status < 0 (a negative errno) carries a UTF-8
 * message (no NUL) as payload; nothing of the request was applied, except
 * the time advance.  A malformed request (bad magic, unknown type, length
 * over VB_MAX_PAYLOAD, payload that does not parse) gets -EINVAL or
 * -EPROTO with a message; a bad magic or oversize length also closes that
 * connection (the stream cannot be re-synchronized).  The board keeps
 * serving its other clients.
 *
 * All multi-byte fields are little-endian.  Structs below are the exact
 * wire layout (packed, natural alignment, no padding surprises: every
 * member is already aligned).
 */
#ifndef VBOARD_PROTO_H
#define VBOARD_PROTO_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define VB_PROTO_VERSION 1u
#define VB_REQ_MAGIC 0x51524256u /* "VBRQ" little-endian */
#define VB_REP_MAGIC 0x50524256u /* "VBRP" little-endian */
#define VB_MAX_PAYLOAD (16u << 20)

struct vb_header {
    uint32_t magic;        /* VB_REQ_MAGIC / VB_REP_MAGIC */
    uint16_t type;         /* enum vb_type; the reply repeats it */
    int16_t status;        /* requests: 0; replies: 0 or -errno */
    uint32_t length;       /* payload bytes after the header */
    uint32_t seq;          /* chosen by the client, echoed in the reply */
    uint64_t time_ns;      /* request: host time (0 = no advance);
                              reply: board time after the request */
};

enum vb_type {
    /* --- identity ---------------------------------------------------- */
    VB_HELLO = 0x01,       /* req: none; rep: struct vb_hello */

    /* --- hm2 local bus (PCI-style boards) ------------------------------ */
    VB_READ = 0x10,        /* req: n x struct vb_xfer; rep: the data of
                              every xfer concatenated, in order */
    VB_WRITE = 0x11,       /* req: n x (struct vb_xfer, size data bytes);
                              rep: none */

    /* --- EPP boards (7i43, Pluto-P): the PC's parallel-port registers -- */
    VB_EPP = 0x20,         /* req: n x (struct vb_epp_op [, n data bytes for
                              EPP_OP_DATA_WRITE]); kinds are
                              enum epp_op_kind of host/driver's epp_port.h.
                              rep: the bytes every read op produced
                              (ADDR_READ 1, DATA_READ n, STATUS_READ 1),
                              concatenated in order.  Cycles run pin-level
                              on the firmware's EPP pins; an EPP cycle whose
                              nWait handshake does not come within 10 us
                              aborts and sets the status timeout bit, as a
                              PC port does; further data cycles are skipped
                              (reads give 0xFF) until the bit is cleared. */
    VB_EPP_STALL = 0x21,   /* req: u32 on (1: the board stops answering EPP
                              handshakes, as a hung or absent board);
                              rep: none */

    /* --- configuration port (local-bus boards; EPP boards are configured
     *     through their own EPP/control-line sequence) ------------------- */
    VB_CONFIG = 0x30,      /* req: struct vb_config [, bitstream bytes];
                              rep: struct vb_config_status */

    /* --- time ---------------------------------------------------------- */
    VB_TIME = 0x40,        /* req: struct vb_time; rep: none (the header's
                              time is the board time) */

    /* --- pins ---------------------------------------------------------- */
    VB_PROBE = 0x50,       /* req: u32 first, u32 count (I/O pin numbers);
                              rep: count x struct vb_pin */
    VB_DRIVE = 0x51,       /* req: n x struct vb_drive; rep: none */
    VB_QUAD = 0x52,        /* req: struct vb_quad; rep: none */
    VB_LOOP = 0x53,        /* req: n x struct vb_loop; rep: none */
    VB_PROBE_RESET = 0x54, /* req: u32 first, u32 count; clears counters and
                              measurements; rep: none */

    /* --- waveforms ----------------------------------------------------- */
    VB_DUMP = 0x60,        /* req: u32 on, then a path (UTF-8, to the end of
                              the payload; .vcd or .fst); rep: none */

    /* --- the machine behind the pins (vboard --machine) ------------------ */
    VB_PLANT = 0x70,       /* req: a text command (UTF-8, the whole payload):
                              "status", "trace PATH", "trace off";
                              rep: JSON text (docs/vboard-machine.md) */
    /* --- Smart Serial remote boards (vboard --sserial P.C=TYPE) --------- */
    VB_SSERIAL = 0x71,     /* req: a text command (the whole payload):
                              "status", "set P.C KEY VALUE...";
                              rep: JSON text (docs/sserial.md) */
    /* --- the FPGA's JTAG port (hm2flash --jtag sim:SOCKET) ------------------ */
    VB_JTAG = 0x80,        /* req: u32 line levels (bit 0 TCK, 1 TMS, 2 TDI)
                              on the FPGA's JTAG port; rep: u32 TDO (bit 0).
                              -ENOTSUP on a board without one */
};

/* ---- VB_HELLO ----------------------------------------------------------- */
enum vb_bus { VB_BUS_LOCAL = 1, VB_BUS_EPP_HM2 = 2, VB_BUS_EPP_PLUTO = 3 };
enum vb_state { VB_STATE_BLANK = 0, VB_STATE_CONFIGURED = 1 };
struct vb_hello {
    uint32_t version;        /* VB_PROTO_VERSION */
    uint32_t bus;            /* enum vb_bus */
    uint32_t state;          /* enum vb_state */
    uint32_t io_pins;        /* I/O pins the probe API knows */
    uint32_t clock_low_hz;   /* 0 while blank */
    uint32_t clock_high_hz;  /* 0 while blank or without a second clock */
    uint32_t lockstep;       /* 1 lockstep, 0 free-running */
    uint32_t reserved;
    char board[16];          /* "5i20", "7i43", "pluto" (NUL padded) */
    char firmware[32];       /* "SVST8_4", "pluto_servo", "" when blank */
    char fpga_part[32];      /* as in a .BIT 'b' chunk: "2s200pq208" */
};

/* ---- VB_READ / VB_WRITE -------------------------------------------------- */
struct vb_xfer {
    uint32_t addr;           /* hm2 byte address, multiple of 4 */
    uint32_t size;           /* bytes, multiple of 4; address increments */
};

/* ---- VB_EPP --------------------------------------------------------------- */
struct vb_epp_op {
    uint8_t kind;            /* enum epp_op_kind (epp_port.h) */
    uint8_t reserved[3];
    uint32_t n;              /* DATA_READ/DATA_WRITE: cycles */
    uint32_t val;            /* ADDR_WRITE, STATUS/CONTROL/SPP/ECR_WRITE,
                                DELAY (ns) */
};

/* ---- VB_CONFIG ------------------------------------------------------------ */
enum vb_config_op {
    VB_CONFIG_STATUS = 0,    /* just report */
    VB_CONFIG_RESET = 1,     /* unconfigure: DONE low, pins tri-stated */
    VB_CONFIG_PROGRAM = 2,   /* the bitstream follows (a .BIT file's 'e'
                                chunk as the file holds it); on a bad image
                                the board stays blank and the reply is
                                -EINVAL with the reason */
};
struct vb_config {
    uint32_t op;             /* enum vb_config_op */
    uint32_t reserved;
};
struct vb_config_status {
    uint32_t done;           /* 1 configured */
    uint32_t init;           /* /INIT: 1 = high (no CRC error) */
    char firmware[32];
};

/* ---- VB_TIME ------------------------------------------------------------- */
enum vb_time_op {
    VB_TIME_ADVANCE = 0,     /* run the clocks for `ns` more nanoseconds */
    VB_TIME_LOCKSTEP = 1,    /* lockstep mode (epochs are re-taken) */
    VB_TIME_FREERUN = 2,     /* free-running with the wall clock */
};
struct vb_time {
    uint32_t op;
    uint32_t reserved;
    uint64_t ns;
};

/* ---- pins ----------------------------------------------------------------- */
/* I/O pin numbers are the IDROM's (hm2: 0..IOWidth-1; Pluto: see
 * docs/vboard.md for the numbering of its pins).  Times are board ns. */
struct vb_pin {
    uint8_t level;           /* what the pin reads now (driven, pulled up) */
    uint8_t oe;              /* the FPGA drives it */
    uint8_t ext;             /* 0 not driven from outside, 1 driven low,
                                2 driven high, 3 looped from another pin,
                                4 quadrature source, 5 the machine model
                                (vboard --machine) */
    uint8_t reserved;
    uint32_t rising;         /* edge counters since reset/probe reset */
    uint32_t falling;
    uint32_t reserved2;
    uint64_t last_high_ns;   /* width of the last complete high pulse */
    uint64_t last_low_ns;    /* width of the last complete low pulse */
    uint64_t period_ns;      /* rising edge to rising edge, last one */
    uint64_t high_total_ns;  /* time spent high since reset (duty) */
    uint64_t total_ns;       /* time observed since reset */
    uint64_t min_high_ns;    /* shortest high / low pulse since reset */
    uint64_t min_low_ns;     /*   (UINT64_MAX when none yet) */
};

enum vb_drive_mode { VB_DRIVE_RELEASE = 0, VB_DRIVE_LOW = 1, VB_DRIVE_HIGH = 2 };
struct vb_drive {
    uint32_t pin;
    uint32_t mode;           /* enum vb_drive_mode */
};

/* A quadrature source on pins a/b (and index, or UINT32_MAX for none):
 * counts per second (signed: direction), index pulse once every
 * `index_every` counts (0: never), rate 0 stops it (pins keep their
 * level).  A new VB_QUAD on the same pin a replaces the old source. */
struct vb_quad {
    uint32_t pin_a, pin_b, pin_index;
    uint32_t index_every;
    double counts_per_s;
};

/* Wire output pin `from` into input pin `to` (to = UINT32_MAX removes every
 * loop from `from`); `invert` 1 inverts. */
struct vb_loop {
    uint32_t from, to;
    uint32_t invert, reserved;
};

#ifdef __cplusplus
}
#endif

#endif /* VBOARD_PROTO_H */
