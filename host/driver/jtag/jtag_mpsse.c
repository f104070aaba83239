/* SPDX-License-Identifier: GPL-2.0-or-later */
/* jtag_mpsse.c - JTAG over an FTDI MPSSE command stream (hm2/jtag_mpsse.h). */
#define _POSIX_C_SOURCE 200809L
#include "hm2/jtag_mpsse.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    MP_BYTES_OUT = 0x19,    /* data bytes out, -ve edge, LSB first */
    MP_BITS_OUT = 0x1B,     /* data bits out */
    MP_BYTES_INOUT = 0x39,  /* bytes out -ve, in +ve */
    MP_BITS_INOUT = 0x3B,   /* bits out -ve, in +ve */
    MP_TMS_OUT = 0x4B,      /* TMS bits out (bit 7 held on TDI) */
    MP_TMS_INOUT = 0x6B,    /* TMS bits out, TDO in on +ve */
    MP_SET_LOW = 0x80,      /* ADBUS value, direction */
    MP_LOOPBACK_OFF = 0x85,
    MP_DIVISOR = 0x86,
    MP_SEND_IMMEDIATE = 0x87,
    MP_DIV5_OFF = 0x8A,
    MP_3PHASE_OFF = 0x8D,
    MP_ADAPTIVE_OFF = 0x97,
};

#define MAX_QUEUE 4096 /* command bytes before an automatic send */

static int bit_of(const uint8_t *v, size_t i)
{
    return (v[i / 8] >> (i % 8)) & 1;
}

static int grow(struct mpsse *m, size_t more)
{
    if (m->ncmd + more <= m->cap)
        return 0;
    size_t cap = m->cap ? m->cap : 1024;
    while (cap < m->ncmd + more)
        cap *= 2;
    uint8_t *p = realloc(m->cmd, cap);
    if (!p)
        return -ENOMEM;
    m->cmd = p;
    m->cap = cap;
    return 0;
}

static int put(struct mpsse *m, const uint8_t *b, size_t n)
{
    int r = grow(m, n);
    if (r)
        return r;
    memcpy(m->cmd + m->ncmd, b, n);
    m->ncmd += n;
    return 0;
}

static int add_read(struct mpsse *m, uint8_t *dst, size_t bit, uint32_t nbits, uint8_t kind)
{
    if (m->nreads == m->capreads) {
        size_t cap = m->capreads ? 2 * m->capreads : 64;
        struct mpsse_read *p = realloc(m->reads, cap * sizeof(*p));
        if (!p)
            return -ENOMEM;
        m->reads = p;
        m->capreads = cap;
    }
    m->reads[m->nreads++] = (struct mpsse_read){dst, bit, nbits, kind};
    m->reply_bytes += kind == 0 ? nbits / 8 : 1;
    return 0;
}

static void set_bit(uint8_t *v, size_t i, int b)
{
    if (b)
        v[i / 8] |= (uint8_t)(1u << (i % 8));
    else
        v[i / 8] &= (uint8_t)~(1u << (i % 8));
}

static const char *terr(struct mpsse *m)
{
    return m->t.error ? m->t.error(m->t.ctx) : "";
}

/* Send the queued commands and distribute the reply. */
static int mp_flush(void *ctx)
{
    struct mpsse *m = ctx;
    if (!m->ncmd)
        return 0;
    int r = 0;
    if (m->reply_bytes) {
        uint8_t si = MP_SEND_IMMEDIATE;
        if ((r = put(m, &si, 1)))
            return r;
    }
    r = m->t.write(m->t.ctx, m->cmd, m->ncmd);
    m->bytes_out += m->ncmd;
    m->ncmd = 0;
    if (r) {
        snprintf(m->err, sizeof(m->err), "sending %s to the cable: %s", "MPSSE commands",
                 terr(m));
        goto out;
    }
    if (m->reply_bytes) {
        uint8_t *rep = malloc(m->reply_bytes);
        if (!rep) {
            r = -ENOMEM;
            goto out;
        }
        r = m->t.read(m->t.ctx, rep, m->reply_bytes);
        if (r) {
            snprintf(m->err, sizeof(m->err), "reading %zu bytes of TDO from the cable: %s",
                     m->reply_bytes, terr(m));
            free(rep);
            goto out;
        }
        size_t pos = 0;
        for (size_t i = 0; i < m->nreads; i++) {
            struct mpsse_read *rd = &m->reads[i];
            if (rd->kind == 0) {
                for (uint32_t b = 0; b < rd->nbits; b++)
                    set_bit(rd->dst, rd->bit + b, (rep[pos + b / 8] >> (b % 8)) & 1);
                pos += rd->nbits / 8;
            } else {
                /* n bits shift in from the top of the byte */
                uint8_t v = (uint8_t)(rep[pos++] >> (8 - rd->nbits));
                for (uint32_t b = 0; b < rd->nbits; b++)
                    set_bit(rd->dst, rd->bit + b, (v >> b) & 1);
            }
        }
        free(rep);
    }
out:
    m->nreads = 0;
    m->reply_bytes = 0;
    return r;
}

/* One TCK with TMS driven through a TMS command (TDI held from bit 7). */
static int tms_bit(struct mpsse *m, int tms, int tdi, uint8_t *tdo, size_t tdo_bit)
{
    uint8_t c[3] = {tdo ? MP_TMS_INOUT : MP_TMS_OUT, 0x00,
                    (uint8_t)((tdi ? 0x80 : 0) | (tms ? 0x01 : 0x00))};
    int r = put(m, c, 3);
    if (!r && tdo)
        r = add_read(m, tdo, tdo_bit, 1, 1);
    m->tms_pin = tms;
    m->commands++;
    return r;
}

/* A run of bits with TMS low (the pin already low). */
static int data_run(struct mpsse *m, const uint8_t *tdi, uint8_t *tdo, size_t first, size_t n)
{
    int r = 0;
    while (!r && n >= 8) {
        size_t bytes = n / 8 > 65536 ? 65536 : n / 8;
        uint8_t c[3] = {tdo ? MP_BYTES_INOUT : MP_BYTES_OUT, (uint8_t)((bytes - 1) & 0xFF),
                        (uint8_t)((bytes - 1) >> 8)};
        if ((r = put(m, c, 3)) || (r = grow(m, bytes)))
            break;
        for (size_t k = 0; k < bytes; k++) {
            uint8_t v = 0;
            for (int b = 0; b < 8; b++)
                v |= (uint8_t)(bit_of(tdi, first + 8 * k + (size_t)b) << b);
            m->cmd[m->ncmd++] = v;
        }
        if (tdo)
            r = add_read(m, tdo, first, (uint32_t)(bytes * 8), 0);
        m->commands++;
        first += bytes * 8;
        n -= bytes * 8;
        if (!r && m->ncmd > MAX_QUEUE)
            r = mp_flush(m);
    }
    if (!r && n) {
        uint8_t v = 0;
        for (size_t b = 0; b < n; b++)
            v |= (uint8_t)(bit_of(tdi, first + b) << b);
        uint8_t c[3] = {tdo ? MP_BITS_INOUT : MP_BITS_OUT, (uint8_t)(n - 1), v};
        r = put(m, c, 3);
        if (!r && tdo)
            r = add_read(m, tdo, first, (uint32_t)n, 1);
        m->commands++;
    }
    return r;
}

static int mp_clock(void *ctx, const uint8_t *tms, const uint8_t *tdi, uint8_t *tdo, size_t n)
{
    struct mpsse *m = ctx;
    size_t i = 0;
    int r = 0;
    m->tck += n;
    while (!r && i < n) {
        if (bit_of(tms, i) || m->tms_pin) {
            r = tms_bit(m, bit_of(tms, i), bit_of(tdi, i), tdo, i);
            i++;
        } else {
            size_t j = i;
            while (j < n && !bit_of(tms, j))
                j++;
            r = data_run(m, tdi, tdo, i, j - i);
            i = j;
        }
        if (!r && m->ncmd > MAX_QUEUE)
            r = mp_flush(m);
    }
    if (r && !m->err[0])
        snprintf(m->err, sizeof(m->err), "%s", strerror(-r));
    return r;
}

static const char *mp_error(void *ctx)
{
    return ((struct mpsse *)ctx)->err;
}

struct jtag_cable mpsse_cable(struct mpsse *m)
{
    return (struct jtag_cable){mp_clock, mp_flush, m, mp_error};
}

int mpsse_open(struct mpsse *m, const struct mpsse_transport *t, uint32_t hz)
{
    memset(m, 0, sizeof(*m));
    m->t = *t;
    if (hz == 0 || hz > 30000000u)
        hz = 30000000u;
    uint32_t div = 30000000u / hz - 1;
    if (div > 0xFFFF)
        div = 0xFFFF;
    /* TCK, TDI, TMS outputs (TMS high), TDO input */
    const uint8_t setup[] = {MP_DIV5_OFF, MP_ADAPTIVE_OFF, MP_3PHASE_OFF,
                             MP_SET_LOW,  0x08,            0x0B,
                             MP_DIVISOR,  (uint8_t)div,    (uint8_t)(div >> 8),
                             MP_LOOPBACK_OFF};
    m->tms_pin = 1;
    int r = put(m, setup, sizeof(setup));
    if (!r)
        r = mp_flush(m);
    return r;
}

void mpsse_close(struct mpsse *m)
{
    free(m->cmd);
    free(m->reads);
    m->cmd = NULL;
    m->reads = NULL;
}
