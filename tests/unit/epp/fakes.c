/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Simulated parallel port + EPP peripherals for the unit tests (fakes.h). */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <sys/ioctl.h>
#include <linux/parport.h>
#include <linux/ppdev.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fakes.h"

static void tracef(char *buf, size_t cap, size_t *len, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void tracef(char *buf, size_t cap, size_t *len, const char *fmt, ...)
{
    if (*len + 64 >= cap)
        return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf + *len, cap - *len, fmt, ap);
    va_end(ap);
    if (n > 0)
        *len += (size_t)n;
}
#define PTRACE(p, ...)                                                     \
    do {                                                                   \
        if ((p)->trace_on)                                                 \
            tracef((p)->trace, sizeof((p)->trace), &(p)->trace_len, __VA_ARGS__); \
    } while (0)

static uint8_t rev8(uint8_t b)
{
    uint8_t r = 0;
    for (int i = 0; i < 8; i++)
        if (b & (1u << i))
            r |= (uint8_t)(0x80u >> i);
    return r;
}

void periph_init(struct periph *p, enum periph_kind kind)
{
    memset(p, 0, sizeof(*p));
    p->kind = kind;
    p->trace_on = 1;
    p->control = 0x04;
    p->prog_b = 1;
}

uint32_t periph_hm2_get(const struct periph *p, uint32_t a)
{
    a &= 0xFFFC;
    return (uint32_t)p->hmem[a] | (uint32_t)p->hmem[a + 1] << 8 | (uint32_t)p->hmem[a + 2] << 16 |
           (uint32_t)p->hmem[a + 3] << 24;
}

void periph_hm2_set(struct periph *p, uint32_t a, uint32_t v)
{
    a &= 0xFFFC;
    for (int i = 0; i < 4; i++)
        p->hmem[a + (uint32_t)i] = (uint8_t)(v >> (8 * i));
}

int periph_addr_write(struct periph *p, uint8_t v)
{
    if (p->stall)
        return 1;
    PTRACE(p, "A(%02x) ", v);
    switch (p->kind) {
    case PERIPH_MEM:
        p->addr = v;
        break;
    case PERIPH_PLUTO:
        p->paddr = v & 0x1F;
        break;
    case PERIPH_7I43:
        if (!p->configured) {
            p->cpld_reg = v & 1;
        } else if (p->addr_hi_next) {
            p->haddr = (uint16_t)((p->haddr & 0x00FF) | v << 8);
            p->addr_hi_next = 0;
        } else {
            p->haddr = (uint16_t)((p->haddr & 0xFF00) | v);
            p->addr_hi_next = 1;
        }
        break;
    }
    return 0;
}

int periph_addr_read(struct periph *p, uint8_t *v)
{
    if (p->stall)
        return 1;
    *v = p->kind == PERIPH_MEM ? p->addr : p->kind == PERIPH_PLUTO ? p->paddr : 0;
    PTRACE(p, "a(%02x) ", *v);
    return 0;
}

static void hm2_step(struct periph *p)
{
    p->addr_hi_next = 0;
    if (p->haddr & 0x8000)
        p->haddr = (uint16_t)(0x8000 | ((p->haddr + 1) & 0x7FFF));
}

int periph_data_write(struct periph *p, uint8_t v)
{
    if (p->stall)
        return 1;
    PTRACE(p, "W(%02x) ", v);
    switch (p->kind) {
    case PERIPH_MEM:
        p->mem[p->addr++] = v;
        break;
    case PERIPH_PLUTO:
        if ((p->paddr & 1) == 0) {
            p->low = v;
        } else {
            int reg = (p->paddr & 0x0F) >> 1;
            p->wreg[reg] = (uint16_t)(v << 8 | p->low);
            p->wcommits[reg]++;
        }
        p->paddr = (p->paddr + 1) & 0x1F;
        break;
    case PERIPH_7I43:
        if (!p->configured) {
            if (p->cpld_reg == 1) {
                p->prog_b = v & 1;
                if (!p->prog_b) {
                    p->cfg_count = 0;
                    p->cfg_bad = 0;
                }
            } else if (p->prog_b) {
                if (p->cfg_count >= p->expect_len ||
                    rev8(p->expect_bits[p->cfg_count]) != v)
                    p->cfg_bad = 1;
                p->cfg_count++;
                if (p->cfg_count == p->expect_len && !p->cfg_bad) {
                    p->configured = 1;
                    p->addr_hi_next = 0;
                }
            }
            break;
        }
        if ((p->haddr & 0xFFFF) == 0x7F7F && v == 0x5A) {
            p->configured = 0;
            p->reconfigs++;
            p->cfg_count = 0;
            p->cpld_reg = 0;
            break;
        }
        {
            uint32_t a = p->haddr & 0x7FFF;
            int lane = (int)(a & 3);
            p->wlatch = (p->wlatch & ~(0xFFu << (8 * lane))) | (uint32_t)v << (8 * lane);
            if (lane == 3)
                periph_hm2_set(p, a, p->wlatch);
            hm2_step(p);
        }
        break;
    }
    return 0;
}

int periph_data_read(struct periph *p, uint8_t *v)
{
    if (p->stall)
        return 1;
    switch (p->kind) {
    case PERIPH_MEM:
        *v = p->mem[p->addr++];
        break;
    case PERIPH_PLUTO: {
        int sel = p->paddr >> 2;
        if ((p->paddr & 3) == 0 && sel < 5) {
            p->snap = p->rreg[sel];
            if (sel < 4 && (p->snap & (1u << 28))) {
                p->rreg[sel] &= ~(1u << 28);
                p->index_reads[sel]++;
            }
        }
        *v = (uint8_t)(p->snap >> (8 * (p->paddr & 3)));
        p->paddr = (p->paddr + 1) & 0x1F;
        break;
    }
    case PERIPH_7I43:
        if (!p->configured) {
            if (p->cpld_reg == 1)
                *v = (p->configured || p->force_done) ? 1 : 0;
            else
                *v = p->size400 ? 1 : 0;
            break;
        }
        {
            uint32_t a = p->haddr & 0x7FFF;
            if ((a & 3) == 0)
                p->rlatch = periph_hm2_get(p, a);
            *v = (uint8_t)(p->rlatch >> (8 * (a & 3)));
            hm2_step(p);
        }
        break;
    }
    PTRACE(p, "R(%02x) ", *v);
    return 0;
}

void periph_control(struct periph *p, uint8_t v)
{
    int ninit_was = (p->control >> 2) & 1, ninit = (v >> 2) & 1;
    if (!ninit)
        p->ninit_low_writes++;
    if (!ninit_was && ninit) {
        p->ninit_pulses++;
        p->ps_bits = 0;
        memset(p->ps_bytes, 0, sizeof(p->ps_bytes));
    }
    /* DCLK = nStrobe pin = NOT control bit 0: sample DATA0 when bit 0 rises */
    if (!(p->control & 1) && (v & 1) && ninit && p->ps_bits < 8 * sizeof(p->ps_bytes)) {
        if (p->spp_data & 1)
            p->ps_bytes[p->ps_bits / 8] |= (uint8_t)(1u << (p->ps_bits % 8));
        p->ps_bits++;
    }
    p->control = v;
}

void periph_spp_data(struct periph *p, uint8_t v)
{
    p->spp_data = v;
}

/* ---- PC port ------------------------------------------------------------ */

void pcport_init(struct pcport *pc, struct periph *p)
{
    memset(pc, 0, sizeof(*pc));
    pc->p = p;
    pc->clear_on_one = 1;
    pc->log_on = 1;
}

uint8_t pcport_in8(struct pcport *pc, int off)
{
    uint8_t v = 0xFF;
    switch (off) {
    case 1:
        return (uint8_t)(0x78 | (pc->timeout ? 1 : 0));
    case 3:
        if (!pc->timeout && periph_addr_read(pc->p, &v))
            pc->timeout = 1, v = 0xFF;
        return v;
    case 4:
        if (!pc->timeout && periph_data_read(pc->p, &v))
            pc->timeout = 1, v = 0xFF;
        return v;
    default:
        return 0xFF;
    }
}

void pcport_out8(struct pcport *pc, int off, uint8_t v)
{
    switch (off) {
    case 0:
        periph_spp_data(pc->p, v);
        break;
    case 1:
        if ((v & 1) == (pc->clear_on_one ? 1 : 0))
            pc->timeout = 0;
        break;
    case 2:
        periph_control(pc->p, v);
        break;
    case 3:
        if (!pc->timeout && periph_addr_write(pc->p, v))
            pc->timeout = 1;
        break;
    case 4:
        if (!pc->timeout && periph_data_write(pc->p, v))
            pc->timeout = 1;
        break;
    case 0x402:
        pc->ecr = v;
        pc->ecr_writes++;
        break;
    }
}

#define PCLOG(pc, ...)                                                     \
    do {                                                                   \
        if ((pc)->log_on)                                                  \
            tracef((pc)->log, sizeof((pc)->log), &(pc)->log_len, __VA_ARGS__); \
    } while (0)

/* ---- raw port instructions ---------------------------------------------- */

static int raw_off(struct fake_raw *f, unsigned long port)
{
    if (port >= f->base && port < f->base + 8)
        return (int)(port - f->base);
    if (port == f->base_hi + 2)
        return 0x402;
    return -1;
}

static int r_ioperm(void *ctx, unsigned long from, unsigned long num, int on)
{
    struct fake_raw *f = ctx;
    f->ioperm_calls++;
    f->last_from = from;
    f->last_num = num;
    if (on && f->ioperm_fail)
        return -EPERM;
    f->perm_on += on ? 1 : -1;
    return 0;
}
static uint8_t r_inb(void *ctx, unsigned long port)
{
    struct fake_raw *f = ctx;
    int off = raw_off(f, port);
    PCLOG(f->pc, "inb(+%d) ", off);
    return pcport_in8(f->pc, off);
}
static uint16_t r_inw(void *ctx, unsigned long port)
{
    struct fake_raw *f = ctx;
    int off = raw_off(f, port);
    PCLOG(f->pc, "inw(+%d) ", off);
    uint16_t lo = pcport_in8(f->pc, off);
    return (uint16_t)(lo | pcport_in8(f->pc, off) << 8);
}
static uint32_t r_inl(void *ctx, unsigned long port)
{
    struct fake_raw *f = ctx;
    int off = raw_off(f, port);
    PCLOG(f->pc, "inl(+%d) ", off);
    if (f->wide_broken)
        return 0xFFFFFFFFu;
    uint32_t v = 0;
    for (int i = 0; i < 4; i++)
        v |= (uint32_t)pcport_in8(f->pc, off) << (8 * i);
    return v;
}
static void r_outb(void *ctx, uint8_t v, unsigned long port)
{
    struct fake_raw *f = ctx;
    int off = raw_off(f, port);
    PCLOG(f->pc, "outb(%02x,+%d) ", v, off);
    pcport_out8(f->pc, off, v);
}
static void r_outw(void *ctx, uint16_t v, unsigned long port)
{
    struct fake_raw *f = ctx;
    int off = raw_off(f, port);
    PCLOG(f->pc, "outw(%04x,+%d) ", v, off);
    pcport_out8(f->pc, off, (uint8_t)v);
    pcport_out8(f->pc, off, (uint8_t)(v >> 8));
}
static void r_outl(void *ctx, uint32_t v, unsigned long port)
{
    struct fake_raw *f = ctx;
    int off = raw_off(f, port);
    PCLOG(f->pc, "outl(%08x,+%d) ", v, off);
    for (int i = 0; i < 4; i++)
        pcport_out8(f->pc, off, (uint8_t)(v >> (8 * i)));
}

struct epp_raw_io fake_raw_io(struct fake_raw *f)
{
    struct epp_raw_io io = {r_ioperm, r_inb, r_inw, r_inl, r_outb, r_outw, r_outl, f};
    return io;
}

/* ---- a batching backend on a pcport ------------------------------------- */

int fake_batch_executes;

static int batch_execute(epp_port_t *port, const struct epp_op *ops, size_t n)
{
    struct pcport *pc = port->priv;
    fake_batch_executes++;
    for (size_t i = 0; i < n; i++) {
        const struct epp_op *op = &ops[i];
        switch (op->kind) {
        case EPP_OP_ADDR_WRITE:
            pcport_out8(pc, 3, (uint8_t)op->val);
            break;
        case EPP_OP_ADDR_READ:
            op->buf[0] = pcport_in8(pc, 3);
            break;
        case EPP_OP_DATA_WRITE:
            for (uint32_t k = 0; k < op->n; k++)
                pcport_out8(pc, 4, op->buf[k]);
            break;
        case EPP_OP_DATA_READ:
            for (uint32_t k = 0; k < op->n; k++)
                op->buf[k] = pcport_in8(pc, 4);
            break;
        case EPP_OP_STATUS_READ:
            op->buf[0] = pcport_in8(pc, 1);
            break;
        case EPP_OP_STATUS_WRITE:
            pcport_out8(pc, 1, (uint8_t)op->val);
            break;
        case EPP_OP_CONTROL_WRITE:
            pcport_out8(pc, 2, (uint8_t)op->val);
            break;
        case EPP_OP_SPP_DATA_WRITE:
            pcport_out8(pc, 0, (uint8_t)op->val);
            break;
        case EPP_OP_ECR_WRITE:
            pcport_out8(pc, 0x402, (uint8_t)op->val);
            break;
        case EPP_OP_DELAY:
            break;
        default:
            return -EINVAL;
        }
    }
    return 0;
}

static const struct epp_backend batch_backend = {"fake", 1, batch_execute, NULL};

int fake_batch_open(epp_port_t *port, struct pcport *pc, int wide)
{
    epp_port_init(port, &batch_backend, pc, "fake:batch", wide);
    port->has_ecr = 1;
    return 0;
}

/* ---- ppdev -------------------------------------------------------------- */

#define PPLOG(f, ...) tracef((f)->calls, sizeof((f)->calls), &(f)->calls_len, __VA_ARGS__)

static int pp_open(void *ctx, const char *path, int flags)
{
    struct fake_ppdev *f = ctx;
    PPLOG(f, "open(%s,%s) ", path, (flags & O_ACCMODE) == O_RDWR ? "rw" : "?");
    return f->open_fail ? -ENOENT : 7;
}
static int pp_close(void *ctx, int fd)
{
    struct fake_ppdev *f = ctx;
    PPLOG(f, "close(%d) ", fd);
    f->closed++;
    return 0;
}
static int pp_ioctl(void *ctx, int fd, unsigned long req, void *arg)
{
    struct fake_ppdev *f = ctx;
    if (fd != 7)
        return -EBADF;
    switch (req) {
    case PPCLAIM:
        PPLOG(f, "PPCLAIM ");
        if (f->claim_fail)
            return -EBUSY;
        f->claimed = 1;
        return 0;
    case PPRELEASE:
        PPLOG(f, "PPRELEASE ");
        f->released = 1;
        return 0;
    case PPSETMODE:
        PPLOG(f, "PPSETMODE(%s%s) ", (*(int *)arg & IEEE1284_MODE_EPP) ? "EPP" : "?",
              (*(int *)arg & IEEE1284_ADDR) ? "|ADDR" : "");
        if (f->mode_fail)
            return -EINVAL;
        f->mode = *(int *)arg;
        return 0;
    case PPSETFLAGS:
        f->flags = *(int *)arg;
        PPLOG(f, "PPSETFLAGS(%s) ",
              f->flags == (PP_FASTWRITE | PP_FASTREAD) ? "FAST" : "?");
        return 0;
    case PPRSTATUS:
        /* the kernel clears a timeout itself: bit 0 never shows here */
        *(uint8_t *)arg = (uint8_t)(pcport_in8(f->pc, 1) & 0xFE);
        PPLOG(f, "PPRSTATUS ");
        return 0;
    case PPWCONTROL:
        PPLOG(f, "PPWCONTROL(%02x) ", *(uint8_t *)arg);
        pcport_out8(f->pc, 2, *(uint8_t *)arg);
        return 0;
    case PPWDATA:
        PPLOG(f, "PPWDATA(%02x) ", *(uint8_t *)arg);
        pcport_out8(f->pc, 0, *(uint8_t *)arg);
        return 0;
    case PPDATADIR:
        PPLOG(f, "PPDATADIR(%d) ", *(int *)arg);
        return 0;
    default:
        return -ENOTTY;
    }
}
/* parport_pc's EPP routines: on a missing acknowledge they clear the
 * timeout and return the count done so far. */
static long pp_xfer(struct fake_ppdev *f, int is_read, uint8_t *buf, size_t n)
{
    int addr = (f->mode & IEEE1284_ADDR) != 0;
    PPLOG(f, "%s%s(%zu) ", is_read ? "read" : "write", addr ? "A" : "", n);
    for (size_t i = 0; i < n; i++) {
        int miss = is_read ? (addr ? periph_addr_read(f->pc->p, &buf[i])
                                   : periph_data_read(f->pc->p, &buf[i]))
                           : (addr ? periph_addr_write(f->pc->p, buf[i])
                                   : periph_data_write(f->pc->p, buf[i]));
        if (miss)
            return (long)i;
    }
    return (long)n;
}
static long pp_read(void *ctx, int fd, void *buf, size_t n)
{
    (void)fd;
    return pp_xfer(ctx, 1, buf, n);
}
static long pp_write(void *ctx, int fd, const void *buf, size_t n)
{
    (void)fd;
    return pp_xfer(ctx, 0, (uint8_t *)buf, n);
}

struct epp_ppdev_sys fake_ppdev_sys(struct fake_ppdev *f)
{
    struct epp_ppdev_sys s = {pp_open, pp_close, pp_ioctl, pp_read, pp_write, f};
    return s;
}

/* ---- GPIO lines --------------------------------------------------------- */

static int peripheral_driving(const struct fake_lines *f)
{
    return f->level[EPP_GPIO_NWRITE] == 1 && f->nwait == 1 &&
           (f->level[EPP_GPIO_NDATASTR] == 0 || f->level[EPP_GPIO_NADDRSTR] == 0);
}

static int l_data_dir(void *ctx, int out)
{
    struct fake_lines *f = ctx;
    if (out && peripheral_driving(f))
        f->bus_conflicts++;
    f->bus_out = out;
    return 0;
}
static int l_data_set(void *ctx, uint8_t v)
{
    struct fake_lines *f = ctx;
    if (!f->bus_out)
        return -EPERM;
    f->bus_host = v;
    periph_spp_data(f->p, v);
    return 0;
}
static int l_data_get(void *ctx, uint8_t *v)
{
    struct fake_lines *f = ctx;
    *v = peripheral_driving(f) ? f->bus_periph : (f->bus_out ? f->bus_host : 0xFF);
    return 0;
}
static uint8_t control_byte(const struct fake_lines *f)
{
    return (uint8_t)((!f->level[EPP_GPIO_NWRITE]) | (!f->level[EPP_GPIO_NDATASTR]) << 1 |
                     f->level[EPP_GPIO_NINIT] << 2 | (!f->level[EPP_GPIO_NADDRSTR]) << 3);
}
static int l_set(void *ctx, int role, int level)
{
    struct fake_lines *f = ctx;
    if (role < 0 || role >= EPP_GPIO_NLINES || role == EPP_GPIO_NWAIT || role < 8)
        return -EINVAL;
    f->set_calls++;
    int was = f->level[role];
    f->level[role] = level ? 1 : 0;
    if ((role == EPP_GPIO_NDATASTR || role == EPP_GPIO_NADDRSTR) && was && !level) {
        int is_read = f->level[EPP_GPIO_NWRITE];
        int miss;
        uint8_t b = 0xFF;
        if (role == EPP_GPIO_NADDRSTR)
            miss = is_read ? periph_addr_read(f->p, &b)
                           : periph_addr_write(f->p, f->bus_out ? f->bus_host : 0xFF);
        else
            miss = is_read ? periph_data_read(f->p, &b)
                           : periph_data_write(f->p, f->bus_out ? f->bus_host : 0xFF);
        if (!miss) {
            f->bus_periph = b;
            f->pending_ack = f->ack_delay + 1;
        }
    } else if ((role == EPP_GPIO_NDATASTR || role == EPP_GPIO_NADDRSTR) && !was && level) {
        f->pending_ack = 0;
        f->nwait = 0;
    } else if (role == EPP_GPIO_NWRITE || role == EPP_GPIO_NINIT) {
        periph_control(f->p, control_byte(f));
    }
    return 0;
}
static int l_get(void *ctx, int role, int *level)
{
    struct fake_lines *f = ctx;
    if (role != EPP_GPIO_NWAIT)
        return -EINVAL;
    if (f->pending_ack > 0 && --f->pending_ack == 0)
        f->nwait = 1;
    *level = f->nwait;
    return 0;
}
static uint64_t l_now(void *ctx)
{
    struct fake_lines *f = ctx;
    f->t += 100;
    return f->t;
}
static void l_close(void *ctx)
{
    struct fake_lines *f = ctx;
    f->closed++;
}

struct epp_gpio_lines fake_gpio_lines(struct fake_lines *f, int has_ninit)
{
    struct epp_gpio_lines l = {l_data_dir, l_data_set, l_data_get, l_set, l_get, l_now,
                               l_close,    f,          has_ninit};
    f->level[EPP_GPIO_NWRITE] = f->level[EPP_GPIO_NDATASTR] = f->level[EPP_GPIO_NADDRSTR] = 1;
    f->level[EPP_GPIO_NINIT] = 1;
    return l;
}
