/* SPDX-License-Identifier: GPL-2.0-or-later */
/* jtag_xilinx.c - volatile configuration of a Xilinx Spartan-3/-6 through
 * JTAG (hm2/jtag_xilinx.h). */
#define _POSIX_C_SOURCE 200809L
#include "hm2/jtag_xilinx.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Load `op` into the IR of device `pos` (0 = nearest TDO) and BYPASS into
 * every other device's (all IRs 6 bits). */
static int load_ir(struct jtag *j, int pos, int ndev, uint8_t op, uint8_t *capture)
{
    uint8_t in[8] = {0}, out[8] = {0};
    size_t nbits = (size_t)ndev * 6;
    for (int d = 0; d < ndev; d++) {
        uint8_t v = d == pos ? op : 0x3F;
        for (int b = 0; b < 6; b++)
            if ((v >> b) & 1)
                in[(6 * d + b) / 8] |= (uint8_t)(1u << ((6 * d + b) % 8));
    }
    int r = jtag_scan_ir(j, in, out, nbits, JTAG_RTI);
    if (!r && capture) {
        uint8_t v = 0;
        for (int b = 0; b < 6; b++)
            v |= (uint8_t)(((out[(6 * pos + b) / 8] >> ((6 * pos + b) % 8)) & 1u) << b);
        *capture = v;
    }
    return r;
}

int jtag_xilinx_program(struct jtag *j, int pos, int ndev, const uint8_t *bits, size_t len,
                        uint8_t *status)
{
    if (pos < 0 || pos >= ndev || ndev > 8)
        return snprintf(j->err, sizeof(j->err), "device %d of a %d-device chain", pos, ndev),
               -EINVAL;
    if (len == 0 || len > (64u << 20))
        return snprintf(j->err, sizeof(j->err), "bitstream of %zu bytes", len), -EINVAL;
    /* .BIT data is MSB first per byte; the scan shifts LSB first.  Each
     * BYPASS device between TDI and the FPGA delays the data by one bit:
     * that many padding bits follow it, so the last data bit arrives. */
    size_t after = (size_t)(ndev - 1 - pos);
    size_t nbits = len * 8 + after;
    uint8_t *v = calloc((nbits + 7) / 8, 1);
    if (!v)
        return snprintf(j->err, sizeof(j->err), "out of memory"), -ENOMEM;
    for (size_t i = 0; i < len; i++)
        for (int b = 0; b < 8; b++)
            if ((bits[i] >> (7 - b)) & 1) {
                size_t k = 8 * i + (size_t)b;
                v[k / 8] |= (uint8_t)(1u << (k % 8));
            }
    uint8_t cap = 0;
    int r = jtag_reset(j);
    if (!r)
        r = load_ir(j, pos, ndev, XILINX_JPROGRAM, NULL);
    if (!r)
        r = jtag_idle(j, 10000); /* the FPGA clears its configuration memory */
    if (!r)
        r = load_ir(j, pos, ndev, XILINX_CFG_IN, NULL);
    if (!r)
        r = jtag_scan_dr(j, v, NULL, nbits, JTAG_RTI);
    if (!r)
        r = load_ir(j, pos, ndev, XILINX_JSTART, NULL);
    if (!r)
        r = jtag_idle(j, 64); /* the startup sequence runs on TCK */
    if (!r)
        r = load_ir(j, pos, ndev, XILINX_BYPASS, &cap);
    free(v);
    if (r)
        return r;
    if (status)
        *status = cap;
    /* Xilinx IR capture: bit 5 DONE (Spartan-6: bit 5; Spartan-3: bit 5),
     * bit 4 INIT; bits 1..0 = 01. */
    if ((cap & 0x03) != 0x01)
        return snprintf(j->err, sizeof(j->err),
                        "the FPGA's IR capture 0x%02X is not ...01: wrong chain position or "
                        "IR length", cap),
               -EIO;
    if (!(cap & XILINX_CAPTURE_DONE))
        return snprintf(j->err, sizeof(j->err),
                        "the FPGA did not assert DONE after configuration (IR capture 0x%02X%s)",
                        cap, cap & XILINX_CAPTURE_INIT ? "" : ", INIT low: CRC error"),
               -EIO;
    return 0;
}
