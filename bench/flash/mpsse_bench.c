/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * mpsse_bench.c - what the JTAG engine asks of a real FT2232H when it loads
 * a full Spartan-6 LX9 bitstream (342,816 bytes) through CFG_IN: MPSSE
 * stream bytes per TCK, commands per bitstream byte, USB bytes, and the
 * load time this implies at 30 MHz TCK (the chip's maximum) and at the
 * engine's default 6 MHz.  The transport counts bytes (no USB).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/jtag.h"
#include "hm2/jtag_mpsse.h"
#include "hm2/jtag_xilinx.h"

struct counter {
    unsigned long long out, in;
};

static int c_write(void *ctx, const uint8_t *buf, size_t n)
{
    (void)buf;
    ((struct counter *)ctx)->out += n;
    return 0;
}

static int c_read(void *ctx, uint8_t *buf, size_t n)
{
    memset(buf, 0, n);
    ((struct counter *)ctx)->in += n;
    return 0;
}

int main(void)
{
    enum { LX9 = 2742528 / 8 };
    uint8_t *bits = malloc(LX9);
    if (!bits)
        return 1;
    for (size_t i = 0; i < LX9; i++)
        bits[i] = (uint8_t)(i * 131u + 7u);
    struct counter cnt = {0, 0};
    struct mpsse_transport t = {c_write, c_read, NULL, &cnt};
    struct mpsse m;
    struct jtag j;
    if (mpsse_open(&m, &t, 30000000)) {
        free(bits);
        return 1;
    }
    struct jtag_cable cab = mpsse_cable(&m);
    jtag_init(&j, &cab);
    unsigned long long out0 = cnt.out, cmd0 = m.commands, tck0 = m.tck;
    uint8_t ir = XILINX_CFG_IN, *v = calloc(LX9, 1);
    for (size_t i = 0; i < LX9; i++) /* MSB first per byte, as CFG_IN wants */
        for (int b = 0; b < 8; b++)
            v[i] |= (uint8_t)(((bits[i] >> (7 - b)) & 1) << b);
    int r = jtag_reset(&j);
    if (!r)
        r = jtag_scan_ir(&j, &ir, NULL, 6, JTAG_RTI);
    if (!r)
        r = jtag_scan_dr(&j, v, NULL, (size_t)LX9 * 8, JTAG_RTI);
    if (r) {
        fprintf(stderr, "mpsse_bench: %s\n", j.err);
        return 1;
    }
    double tck = (double)(m.tck - tck0), bytes = (double)(cnt.out - out0);
    double cmds = (double)(m.commands - cmd0);
    printf("JTAG CFG_IN of a %d-byte LX9 bitstream through the MPSSE engine:\n", LX9);
    printf("  TCK cycles           %.0f\n", tck);
    printf("  MPSSE bytes to USB   %.0f (%.4f per TCK, %.4f per bitstream byte)\n", bytes,
           bytes / tck, bytes / LX9);
    printf("  MPSSE commands       %.0f (%.6f per bitstream byte)\n", cmds, cmds / LX9);
    printf("  load time at 30 MHz TCK  %.3f s (USB needs %.2f MB/s; FT2232H bulk ~30-40 MB/s)\n",
           tck / 30e6, bytes / (tck / 30e6) / 1e6);
    printf("  load time at  6 MHz TCK  %.3f s (the engine's default)\n", tck / 6e6);
    mpsse_close(&m);
    free(v);
    free(bits);
    return 0;
}
