/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * jtag_xilinx.h - volatile configuration of a Xilinx Spartan-3 / Spartan-6
 * FPGA through JTAG: JPROGRAM (clear), CFG_IN (shift the .BIT file's 'e'
 * data, MSB of each byte first), JSTART (startup clocks), then the IR
 * capture tells DONE and INIT.  6-bit instruction registers; the other
 * devices of the chain are put in BYPASS.
 */
#ifndef HM2_JTAG_XILINX_H
#define HM2_JTAG_XILINX_H

#include <stddef.h>
#include <stdint.h>

#include "hm2/jtag.h"

#ifdef __cplusplus
extern "C" {
#endif

#define XILINX_CFG_IN 0x05u
#define XILINX_IDCODE 0x09u
#define XILINX_JPROGRAM 0x0Bu
#define XILINX_JSTART 0x0Cu
#define XILINX_BYPASS 0x3Fu
#define XILINX_CAPTURE_DONE 0x20u
#define XILINX_CAPTURE_INIT 0x10u

/* Configure device `pos` (0 = nearest TDO, as jtag_scan_chain lists them)
 * of an `ndev`-device chain of 6-bit-IR parts with `bits` (len bytes).
 * 0 when DONE came up; -EIO with the IR capture in j->err otherwise;
 * *status (may be NULL) gets the final IR capture. */
int jtag_xilinx_program(struct jtag *j, int pos, int ndev, const uint8_t *bits, size_t len,
                        uint8_t *status);

#ifdef __cplusplus
}
#endif

#endif /* HM2_JTAG_XILINX_H */
