/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * sserial.h - Smart Serial inside the hostmot2 driver: the port/channel
 * machinery (sserial.c) and the remote board types it knows
 * (sserial_7i76.c), docs/sserial.md.
 *
 * Register map of one port (hm2_sserial.v, spec/hostmot2.md §9.9): reg 0
 * Command, 1 Data, 2 CS (per channel), 3/4/5 Interface 0/1/2 (per channel,
 * process data: bits 31..0 / 63..32 / 95..64).
 */
#ifndef HM2_SSERIAL_H
#define HM2_SSERIAL_H

#include "module_api.h"

#define SS_REG_CMD 0
#define SS_REG_DATA 1
#define SS_REG_CS 2
#define SS_REG_IF0 3
#define SS_MAX_CHANNELS 8

/* Port commands (hm2_sserial.v) */
#define SS_CMD_STOP 0x0800u
#define SS_CMD_START_NORMAL 0x0A00u
#define SS_CMD_DOIT 0x1000u
#define SS_CMD_READ_LOCAL 0x2000u

struct ss_chan;

/* A remote board type: exports its HAL objects and converts process data. */
struct ss_remote_type {
    const char *name; /* "7i76": the remote's discovery name, lower case */
    /* Export pins/params under prefix ("hm2_5i25.0.7i76.0.0"); 0 or -errno. */
    int (*setup)(hostmot2_t *hm2, struct ss_chan *ch, const char *prefix);
    /* Host -> remote process data, from the HAL pins. */
    void (*pack)(struct ss_chan *ch, uint32_t out[3]);
    /* Remote -> host process data, to the HAL pins. */
    void (*unpack)(struct ss_chan *ch, const uint32_t in[3]);
};

struct ss_chan {
    int port, chan;
    int mode;       /* 0..9 */
    uint32_t unit;  /* the remote's serial number */
    int in_bits, out_bits;
    const struct ss_remote_type *type;
    void *hal;      /* the type's HAL objects (hal_malloc'd) */
    /* TRAM: CS and the three interface registers, read and written */
    uint32_t *rd_cs, *rd_if[3], *wr_if[3];
};

extern const struct ss_remote_type hm2_ss_7i76, hm2_ss_7i77;

#endif
