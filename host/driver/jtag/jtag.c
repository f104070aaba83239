/* SPDX-License-Identifier: GPL-2.0-or-later */
/* jtag.c - TAP state machine, scans and chain IDCODE scan (hm2/jtag.h). */
#define _POSIX_C_SOURCE 200809L
#include "hm2/jtag.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* IEEE 1149.1 figure 6-1: next state for TMS = 0 and TMS = 1. */
static const uint8_t next_state[JTAG_NUM_STATES][2] = {
    [JTAG_TLR] = {JTAG_RTI, JTAG_TLR},
    [JTAG_RTI] = {JTAG_RTI, JTAG_SELECT_DR},
    [JTAG_SELECT_DR] = {JTAG_CAPTURE_DR, JTAG_SELECT_IR},
    [JTAG_CAPTURE_DR] = {JTAG_SHIFT_DR, JTAG_EXIT1_DR},
    [JTAG_SHIFT_DR] = {JTAG_SHIFT_DR, JTAG_EXIT1_DR},
    [JTAG_EXIT1_DR] = {JTAG_PAUSE_DR, JTAG_UPDATE_DR},
    [JTAG_PAUSE_DR] = {JTAG_PAUSE_DR, JTAG_EXIT2_DR},
    [JTAG_EXIT2_DR] = {JTAG_SHIFT_DR, JTAG_UPDATE_DR},
    [JTAG_UPDATE_DR] = {JTAG_RTI, JTAG_SELECT_DR},
    [JTAG_SELECT_IR] = {JTAG_CAPTURE_IR, JTAG_TLR},
    [JTAG_CAPTURE_IR] = {JTAG_SHIFT_IR, JTAG_EXIT1_IR},
    [JTAG_SHIFT_IR] = {JTAG_SHIFT_IR, JTAG_EXIT1_IR},
    [JTAG_EXIT1_IR] = {JTAG_PAUSE_IR, JTAG_UPDATE_IR},
    [JTAG_PAUSE_IR] = {JTAG_PAUSE_IR, JTAG_EXIT2_IR},
    [JTAG_EXIT2_IR] = {JTAG_SHIFT_IR, JTAG_UPDATE_IR},
    [JTAG_UPDATE_IR] = {JTAG_RTI, JTAG_SELECT_DR},
};

static const char *const state_names[JTAG_NUM_STATES] = {
    "Test-Logic-Reset", "Run-Test/Idle", "Select-DR-Scan", "Capture-DR", "Shift-DR",
    "Exit1-DR", "Pause-DR", "Exit2-DR", "Update-DR", "Select-IR-Scan", "Capture-IR",
    "Shift-IR", "Exit1-IR", "Pause-IR", "Exit2-IR", "Update-IR"};

enum jtag_state jtag_next_state(enum jtag_state s, int tms)
{
    return (enum jtag_state)next_state[s][tms ? 1 : 0];
}

const char *jtag_state_name(enum jtag_state s)
{
    return s < JTAG_NUM_STATES ? state_names[s] : "?";
}

/* Breadth-first search over the 16 states. */
int jtag_tms_path(enum jtag_state from, enum jtag_state to, uint8_t *tms)
{
    int prev[JTAG_NUM_STATES], bit[JTAG_NUM_STATES], queue[JTAG_NUM_STATES];
    for (int i = 0; i < JTAG_NUM_STATES; i++)
        prev[i] = -1;
    int head = 0, tail = 0;
    queue[tail++] = from;
    prev[from] = from;
    while (head < tail && prev[to] < 0) {
        int s = queue[head++];
        for (int t = 0; t < 2; t++) {
            int n = next_state[s][t];
            if (prev[n] < 0) {
                prev[n] = s;
                bit[n] = t;
                queue[tail++] = n;
            }
        }
    }
    int path[JTAG_NUM_STATES], len = 0;
    for (int s = to; s != (int)from; s = prev[s])
        path[len++] = bit[s];
    *tms = 0;
    for (int i = 0; i < len; i++)
        *tms |= (uint8_t)(path[len - 1 - i] << i);
    return len;
}

static int fail(struct jtag *j, int rc, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail(struct jtag *j, int rc, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(j->err, sizeof(j->err), fmt, ap);
    va_end(ap);
    return rc;
}

static int cable_failed(struct jtag *j, int rc, const char *what)
{
    const char *why = j->cable.error ? j->cable.error(j->cable.ctx) : "";
    j->state_known = 0;
    return fail(j, rc, "JTAG %s failed: %s", what, why && *why ? why : strerror(-rc));
}

void jtag_init(struct jtag *j, const struct jtag_cable *cable)
{
    memset(j, 0, sizeof(*j));
    j->cable = *cable;
}

static int flush(struct jtag *j, int r, const char *what)
{
    if (r)
        return r;
    r = j->cable.flush(j->cable.ctx);
    return r ? cable_failed(j, r, what) : 0;
}

static int clock_tms(struct jtag *j, uint8_t tms, int n, const char *what)
{
    uint8_t tdi = 0;
    int r = j->cable.clock(j->cable.ctx, &tms, &tdi, NULL, (size_t)n);
    if (r)
        return cable_failed(j, r, what);
    for (int i = 0; i < n; i++)
        j->state = jtag_next_state(j->state, (tms >> i) & 1);
    return 0;
}

int jtag_reset(struct jtag *j)
{
    j->state = JTAG_TLR;
    int r = flush(j, clock_tms(j, 0x1F, 5, "reset"), "reset");
    j->state = JTAG_TLR;
    j->state_known = r == 0;
    return r;
}

int jtag_goto(struct jtag *j, enum jtag_state to)
{
    if (!j->state_known)
        return fail(j, -EINVAL, "JTAG state unknown: reset first");
    uint8_t tms;
    int n = jtag_tms_path(j->state, to, &tms);
    return flush(j, n ? clock_tms(j, tms, n, "state change") : 0, "state change");
}

int jtag_idle(struct jtag *j, size_t n)
{
    int r = jtag_goto(j, JTAG_RTI);
    uint8_t zero[64] = {0};
    while (!r && n) {
        size_t k = n > 512 ? 512 : n;
        r = j->cable.clock(j->cable.ctx, zero, zero, NULL, k);
        if (r)
            return cable_failed(j, r, "idle clocks");
        n -= k;
    }
    return flush(j, r, "idle clocks");
}

static int scan(struct jtag *j, enum jtag_state shift, const uint8_t *in, uint8_t *out,
                size_t nbits, enum jtag_state end)
{
    if (nbits == 0)
        return fail(j, -EINVAL, "JTAG scan of 0 bits");
    int r = jtag_goto(j, shift);
    if (r)
        return r;
    size_t nbytes = (nbits + 7) / 8;
    uint8_t *tms = calloc(nbytes, 1);
    uint8_t *zero = in ? NULL : calloc(nbytes, 1);
    if (!tms || (!in && !zero)) {
        free(tms);
        free(zero);
        return fail(j, -ENOMEM, "out of memory for a %zu-bit scan", nbits);
    }
    tms[(nbits - 1) / 8] |= (uint8_t)(1u << ((nbits - 1) % 8)); /* last bit: to Exit1 */
    r = j->cable.clock(j->cable.ctx, tms, in ? in : zero, out, nbits);
    free(tms);
    free(zero);
    if (r)
        return cable_failed(j, r, "scan");
    j->state = shift == JTAG_SHIFT_IR ? JTAG_EXIT1_IR : JTAG_EXIT1_DR;
    return jtag_goto(j, end); /* flushes: out is filled */
}

int jtag_scan_ir(struct jtag *j, const uint8_t *in, uint8_t *out, size_t nbits,
                 enum jtag_state end)
{
    return scan(j, JTAG_SHIFT_IR, in, out, nbits, end);
}

int jtag_scan_dr(struct jtag *j, const uint8_t *in, uint8_t *out, size_t nbits,
                 enum jtag_state end)
{
    return scan(j, JTAG_SHIFT_DR, in, out, nbits, end);
}

int jtag_scan_chain(struct jtag *j, uint32_t *ids, int max, int *n)
{
    enum { MAXBITS = 32 * 33 };
    uint8_t in[MAXBITS / 8], out[MAXBITS / 8];
    memset(in, 0xFF, sizeof(in));
    memset(out, 0, sizeof(out));
    *n = 0;
    if (max > 32)
        max = 32;
    if (max < 1)
        return fail(j, -EINVAL, "JTAG chain scan: no room for any device");
    int r = jtag_reset(j);
    if (!r)
        r = jtag_scan_dr(j, in, out, (size_t)32 * ((size_t)max + 1), JTAG_RTI);
    if (r)
        return r;
    size_t total = (size_t)32 * ((size_t)max + 1), pos = 0;
    int ones = 1, zeros = 1;
    for (size_t i = 0; i < total / 8; i++) {
        ones &= out[i] == 0xFF;
        zeros &= out[i] == 0x00;
    }
    if (ones || zeros)
        return fail(j, -EIO, "JTAG chain reads all %s: TDO stuck %s (cable not connected, "
                             "board not powered?)", ones ? "ones" : "zeros",
                    ones ? "high" : "low");
    while (pos + 32 <= total) {
        uint32_t w = 0;
        for (int b = 0; b < 32; b++)
            w |= (uint32_t)((out[(pos + (size_t)b) / 8] >> ((pos + (size_t)b) % 8)) & 1u) << b;
        if (w == 0xFFFFFFFFu)
            return 0; /* TDI's ones came through: end of the chain */
        if (*n >= max)
            return fail(j, -E2BIG, "JTAG chain has more than %d devices", max);
        if (w & 1u) {
            ids[(*n)++] = w;
            pos += 32;
        } else {
            ids[(*n)++] = 0; /* a device in BYPASS */
            pos += 1;
        }
    }
    return fail(j, -EIO, "JTAG chain: no end found within %zu bits", total);
}

/* IDCODEs of Xilinx parts on Mesa boards (bits 27..0; IR length 6). */
static const struct jtag_part parts[] = {
    {0x01414093u, "XC3S200", 6},  {0x0141C093u, "XC3S400", 6},
    {0x01428093u, "XC3S1000", 6}, {0x01434093u, "XC3S1500", 6},
    {0x01440093u, "XC3S2000", 6}, {0x04001093u, "XC6SLX9", 6},
    {0x04002093u, "XC6SLX16", 6}, {0x04004093u, "XC6SLX25", 6},
};

const struct jtag_part *jtag_part_by_idcode(uint32_t idcode)
{
    for (size_t i = 0; i < sizeof(parts) / sizeof(parts[0]); i++)
        if ((idcode & 0x0FFFFFFFu) == (parts[i].idcode & 0x0FFFFFFFu))
            return &parts[i];
    return NULL;
}
