/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * vpp_model.c - registers and pins of the virtual parallel port: what the
 * port drives for a given register state, the pin levels with the outside
 * drivers, register reads from pin levels, and the log (see vpp.h).
 */
#include <errno.h>
#include <string.h>

#include "vpp.h"

#define LOAD(p) __atomic_load_n((p), __ATOMIC_ACQUIRE)
#define STORE(p, v) __atomic_store_n((p), (v), __ATOMIC_RELEASE)
#define ADD(p, v) __atomic_fetch_add((p), (v), __ATOMIC_ACQ_REL)

/* Power-on control register: nInit high, nSelectIn asserted, as the PC
 * BIOS and Linux's parport_pc leave a port. */
#define VPP_CONTROL_RESET 0x0cu

struct drive {
    uint32_t mask;  /* pins the port drives (or pulls low, open collector) */
    uint32_t level; /* at which level */
};

/* The data drivers are off when the direction bit is set on a port that
 * honours it: not an SPP-only port, and on an ECR port not in mode 000. */
static int data_drivers_off(uint32_t opts, uint32_t control, uint32_t ecr)
{
    if (!(control & 0x20u) || (opts & VPP_OPT_NO_BIDIR))
        return 0;
    if ((opts & VPP_OPT_ECR) && ((ecr >> 5) & 7u) == 0)
        return 0;
    return 1;
}

static struct drive port_drive(uint32_t opts, uint32_t data, uint32_t control, uint32_t ecr)
{
    struct drive d = {0, 0};
    if (!data_drivers_off(opts, control, ecr)) {
        d.mask |= VPP_DATA_PINS;
        d.level |= (data & 0xffu) << 2;
    }
    /* what the port puts on each control pin (bits 0, 1, 3 inverted) */
    uint32_t out = 0;
    if (!(control & 0x01u))
        out |= VPP_PIN(1);
    if (!(control & 0x02u))
        out |= VPP_PIN(14);
    if (control & 0x04u)
        out |= VPP_PIN(16);
    if (!(control & 0x08u))
        out |= VPP_PIN(17);
    if (opts & VPP_OPT_CONTROL_PP) {
        d.mask |= VPP_CONTROL_PINS;
        d.level |= out;
    } else {
        d.mask |= VPP_CONTROL_PINS & ~out; /* open collector: only pulls low */
    }
    return d;
}

static uint32_t resolve(struct drive d, uint32_t ext_drive, uint32_t ext_level,
                        uint32_t *contention)
{
    uint32_t pins = VPP_ALL_PINS; /* pulled up */
    pins = (pins & ~ext_drive) | (ext_level & ext_drive);
    pins = (pins & ~d.mask) | (d.level & d.mask);
    if (contention)
        *contention = d.mask & ext_drive & (d.level ^ ext_level);
    return pins & VPP_ALL_PINS;
}

static struct drive state_drive(const struct vpp_state *st)
{
    return port_drive(LOAD(&st->options), LOAD(&st->data_latch), LOAD(&st->control_latch),
                      LOAD(&st->ecr));
}

uint32_t vpp_port_drive(const struct vpp_state *st, uint32_t *level)
{
    struct drive d = state_drive(st);
    if (level)
        *level = d.level & d.mask;
    return d.mask;
}

uint32_t vpp_pins(const struct vpp_state *st)
{
    return resolve(state_drive(st), LOAD(&st->ext_drive), LOAD(&st->ext_level), NULL);
}

static void log_append(struct vpp_state *st, uint64_t t_ns, uint32_t pins)
{
    uint64_t n = ADD(&st->log_head, 1);
    struct vpp_log_entry *e = &st->log[n % VPP_LOG_LEN];
    STORE(&e->seq, 0u);
    STORE(&e->t_ns, t_ns);
    STORE(&e->pins, pins);
    STORE(&e->seq, (uint32_t)(n + 1));
}

/* After a change by either side: count contention, log a host change. */
static void settle(struct vpp_state *st, int host, uint64_t t_ns)
{
    uint32_t c = 0;
    uint32_t pins = resolve(state_drive(st), LOAD(&st->ext_drive), LOAD(&st->ext_level), &c);
    if (c)
        ADD(&st->contention, 1);
    if (host && pins != LOAD(&st->last_pins)) {
        STORE(&st->last_pins, pins);
        log_append(st, t_ns, pins);
    } else if (!host) {
        STORE(&st->last_pins, pins);
    }
}

static int reg_index(unsigned offset)
{
    switch (offset) {
    case 0:
        return VPP_REG_DATA;
    case 1:
        return VPP_REG_STATUS;
    case 2:
        return VPP_REG_CONTROL;
    case VPP_ECR_OFFSET:
        return VPP_REG_ECR;
    default:
        return VPP_REG_OTHER;
    }
}

static uint8_t status_of(uint32_t pins)
{
    uint8_t s = 0x06u; /* bits 2-1 read 1, bit 0 (timeout) 0 */
    if (!(pins & VPP_PIN(11)))
        s |= 0x80u;
    if (pins & VPP_PIN(10))
        s |= 0x40u;
    if (pins & VPP_PIN(12))
        s |= 0x20u;
    if (pins & VPP_PIN(13))
        s |= 0x10u;
    if (pins & VPP_PIN(15))
        s |= 0x08u;
    return s;
}

static uint8_t control_of(uint32_t pins, uint32_t latch)
{
    uint8_t c = (uint8_t)(0xc0u | (latch & 0x30u));
    if (!(pins & VPP_PIN(1)))
        c |= 0x01u;
    if (!(pins & VPP_PIN(14)))
        c |= 0x02u;
    if (pins & VPP_PIN(16))
        c |= 0x04u;
    if (!(pins & VPP_PIN(17)))
        c |= 0x08u;
    return c;
}

uint8_t vpp_inb(struct vpp_state *st, unsigned offset, uint64_t t_ns)
{
    int reg = reg_index(offset);
    ADD(&st->reads[reg], 1);
    STORE(&st->last_t_ns, t_ns);
    uint32_t pins = vpp_pins(st);
    switch (reg) {
    case VPP_REG_DATA:
        return (uint8_t)((pins >> 2) & 0xffu);
    case VPP_REG_STATUS:
        return status_of(pins);
    case VPP_REG_CONTROL:
        return control_of(pins, LOAD(&st->control_latch));
    case VPP_REG_ECR:
        if (!(LOAD(&st->options) & VPP_OPT_ECR))
            return 0xffu;
        return (uint8_t)((LOAD(&st->ecr) & 0xfcu) | 0x01u);
    default:
        return 0xffu; /* nothing answers: the bus floats high */
    }
}

void vpp_outb(struct vpp_state *st, unsigned offset, uint8_t v, uint64_t t_ns)
{
    int reg = reg_index(offset);
    ADD(&st->writes[reg], 1);
    STORE(&st->last_t_ns, t_ns);
    switch (reg) {
    case VPP_REG_DATA:
        STORE(&st->data_latch, (uint32_t)v);
        break;
    case VPP_REG_CONTROL:
        STORE(&st->control_latch, (uint32_t)(v & 0x3fu));
        break;
    case VPP_REG_ECR:
        if (!(LOAD(&st->options) & VPP_OPT_ECR))
            return;
        STORE(&st->ecr, (uint32_t)(v & 0xfcu));
        break;
    default:
        return; /* status is read only; nothing else is decoded */
    }
    settle(st, 1, t_ns);
}

int vpp_drive(struct vpp_state *st, int pin, int level)
{
    if (pin < 1 || pin > 17)
        return -EINVAL;
    uint32_t bit = VPP_PIN(pin);
    if (level < 0) {
        __atomic_fetch_and(&st->ext_drive, ~bit, __ATOMIC_ACQ_REL);
    } else {
        if (level)
            __atomic_fetch_or(&st->ext_level, bit, __ATOMIC_ACQ_REL);
        else
            __atomic_fetch_and(&st->ext_level, ~bit, __ATOMIC_ACQ_REL);
        __atomic_fetch_or(&st->ext_drive, bit, __ATOMIC_ACQ_REL);
    }
    settle(st, 0, 0);
    return 0;
}

uint64_t vpp_log_head(const struct vpp_state *st)
{
    return LOAD(&st->log_head);
}

size_t vpp_log_read(const struct vpp_state *st, uint64_t from, struct vpp_log_entry *out,
                    size_t max, uint64_t *first)
{
    uint64_t head = LOAD(&st->log_head), base = LOAD(&st->log_base);
    if (from < base)
        from = base;
    if (head > VPP_LOG_LEN && from < head - VPP_LOG_LEN)
        from = head - VPP_LOG_LEN;
    *first = from;
    size_t n = 0;
    for (uint64_t i = from; i < head && n < max; i++) {
        const struct vpp_log_entry *e = &st->log[i % VPP_LOG_LEN];
        if (LOAD(&e->seq) != (uint32_t)(i + 1))
            break; /* being written, or overwritten meanwhile */
        out[n].t_ns = LOAD(&e->t_ns);
        out[n].pins = LOAD(&e->pins);
        out[n].seq = (uint32_t)(i + 1);
        if (LOAD(&e->seq) != (uint32_t)(i + 1))
            break;
        n++;
    }
    return n;
}

void vpp_log_clear(struct vpp_state *st)
{
    STORE(&st->log_base, LOAD(&st->log_head));
}

void vpp_counters_reset(struct vpp_state *st)
{
    for (int i = 0; i < VPP_NREGS; i++) {
        STORE(&st->reads[i], 0u);
        STORE(&st->writes[i], 0u);
    }
    STORE(&st->contention, 0u);
}

/* Used by vpp_file.c when a port is created. */
void vpp_model_reset(struct vpp_state *st, unsigned options);
void vpp_model_reset(struct vpp_state *st, unsigned options)
{
    st->options = options;
    st->data_latch = 0;
    st->control_latch = VPP_CONTROL_RESET;
    st->ecr = (options & VPP_OPT_ECR) ? VPP_ECR_RESET & 0xfcu : 0;
    st->ext_drive = 0;
    st->ext_level = 0;
    st->last_pins = resolve(state_drive(st), 0, 0, NULL);
}
