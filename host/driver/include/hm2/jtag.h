/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * jtag.h - a JTAG (IEEE 1149.1) engine: the TAP state machine, IR/DR scans
 * and the IDCODE scan of a chain, over a cable that clocks TMS/TDI bits and
 * returns TDO bits.  Cables: FTDI MPSSE (jtag_mpsse.h).  No HAL calls.
 *
 * Bit vectors are LSB first: bit i of a vector is byte i/8, bit i%8; the
 * first bit shifted is bit 0.  Functions return 0 or a negative errno with
 * the reason in j->err.
 */
#ifndef HM2_JTAG_H
#define HM2_JTAG_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum jtag_state {
    JTAG_TLR,
    JTAG_RTI,
    JTAG_SELECT_DR,
    JTAG_CAPTURE_DR,
    JTAG_SHIFT_DR,
    JTAG_EXIT1_DR,
    JTAG_PAUSE_DR,
    JTAG_EXIT2_DR,
    JTAG_UPDATE_DR,
    JTAG_SELECT_IR,
    JTAG_CAPTURE_IR,
    JTAG_SHIFT_IR,
    JTAG_EXIT1_IR,
    JTAG_PAUSE_IR,
    JTAG_EXIT2_IR,
    JTAG_UPDATE_IR,
    JTAG_NUM_STATES
};

/* The state after one TCK with TMS = tms. */
enum jtag_state jtag_next_state(enum jtag_state s, int tms);
const char *jtag_state_name(enum jtag_state s);
/* The shortest TMS sequence from one state to another (at most 8 bits: Select-IR-Scan to Exit2-DR,
 * LSB first in *tms); returns its length. */
int jtag_tms_path(enum jtag_state from, enum jtag_state to, uint8_t *tms);

struct jtag_cable {
    /* Clock n bits: TMS and TDI from the vectors, TDO into tdo when it is
     * not NULL (the cable may defer the transfer until flush). */
    int (*clock)(void *ctx, const uint8_t *tms, const uint8_t *tdi, uint8_t *tdo, size_t n);
    /* Complete every deferred transfer (TDO vectors filled). */
    int (*flush)(void *ctx);
    void *ctx;
    /* The cable's last error text (for j->err). */
    const char *(*error)(void *ctx);
};

struct jtag {
    struct jtag_cable cable;
    enum jtag_state state;
    int state_known; /* 0 until the first reset */
    char err[256];
};

void jtag_init(struct jtag *j, const struct jtag_cable *cable);
/* Five TCKs with TMS high: Test-Logic-Reset from anywhere. */
int jtag_reset(struct jtag *j);
int jtag_goto(struct jtag *j, enum jtag_state to);
/* Shift nbits through IR (or DR), from Run-Test/Idle or any stable state,
 * ending in `end` (JTAG_RTI, JTAG_PAUSE_DR/IR, ...).  out may be NULL. */
int jtag_scan_ir(struct jtag *j, const uint8_t *in, uint8_t *out, size_t nbits,
                 enum jtag_state end);
int jtag_scan_dr(struct jtag *j, const uint8_t *in, uint8_t *out, size_t nbits,
                 enum jtag_state end);
/* n TCKs in Run-Test/Idle. */
int jtag_idle(struct jtag *j, size_t n);

/* After Test-Logic-Reset every device's DR is its IDCODE (32 bits, LSB 1)
 * or BYPASS (1 bit, 0).  Reads the chain from TDO (the device nearest TDO
 * first) until 32 ones in a row (the end: TDI is held high).  Fills ids
 * (0 for a device in BYPASS) and *n; -EIO when the chain reads all zeros
 * or all ones (TDO stuck: no cable, no power). */
int jtag_scan_chain(struct jtag *j, uint32_t *ids, int max, int *n);

struct jtag_part {
    uint32_t idcode; /* version nibble (bits 31..28) ignored */
    const char *name;
    int ir_len;
};
/* Known FPGA parts (Xilinx Spartan-3/-6 of the Mesa boards); NULL if not. */
const struct jtag_part *jtag_part_by_idcode(uint32_t idcode);

#ifdef __cplusplus
}
#endif

#endif /* HM2_JTAG_H */
