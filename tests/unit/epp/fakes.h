/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * fakes.h - simulated hardware for the EPP unit tests: a PC parallel port
 * (registers, timeout bit) in front of an EPP peripheral model, and the
 * lower layers of the three direct backends (port instructions, ppdev
 * system calls, GPIO lines) wired to it.  The peripheral models are written
 * from the specs (spec/pluto.md §2, §3, §5, §8; spec/hostmot2.md §17.2),
 * independently of the driver code under test.
 */
#ifndef EPP_FAKES_H
#define EPP_FAKES_H

#include <stddef.h>
#include <stdint.h>

#include "hm2/epp_port.h"

enum periph_kind {
    PERIPH_MEM,   /* 8-bit address, 256 bytes, auto-increment on data cycles */
    PERIPH_PLUTO, /* Pluto-P front end (servo or step register decode) */
    PERIPH_7I43,  /* CPLD when blank, hm2 EPP bridge when configured */
};

struct periph {
    enum periph_kind kind;
    int stall;      /* 1: never acknowledge (EPP timeout) */
    /* trace of bus cycles: "A(00) W(12) R(34) ..." */
    char trace[65536];
    size_t trace_len;
    int trace_on;
    /* MEM */
    uint8_t addr;
    uint8_t mem[256];
    /* PLUTO */
    int pluto_step;          /* 1: pluto_step write decode */
    uint8_t paddr;           /* 5 bits */
    uint8_t low;             /* write low-byte latch */
    uint16_t wreg[8];        /* committed 16-bit write registers (addr/2) */
    int wcommits[8];
    uint32_t rreg[5];        /* read registers (encoder/stepgen words, inputs) */
    uint32_t snap;
    int index_reads[4];      /* how often bit 28 was cleared by a snapshot */
    /* Passive-serial configuration (pluto): watched on control/data writes */
    uint8_t control, spp_data;
    int ninit_low_writes;    /* control writes with nInit (bit 2) low */
    int ninit_pulses;        /* low->high transitions of nInit */
    uint8_t ps_bytes[40000];
    size_t ps_bits;          /* bits clocked since the last nCONFIG pulse */
    /* 7I43 */
    int configured;
    int size400;             /* CPLD size bit */
    int cpld_reg;            /* selected CPLD register */
    int prog_b;
    const uint8_t *expect_bits; /* expected bitstream (file order) */
    size_t expect_len;
    size_t cfg_count;        /* bytes received since PROG_B */
    int cfg_bad;             /* a byte differed from expect_bits reversed */
    int force_done;          /* DONE reads 1 even when not configured */
    uint16_t haddr;          /* hm2 address register incl. bit 15 */
    int addr_hi_next;        /* next address write sets the high byte */
    uint32_t wlatch, rlatch;
    uint8_t hmem[65536];
    int reconfigs;
};

void periph_init(struct periph *p, enum periph_kind kind);
/* One cycle.  Return 0 = acknowledged, 1 = no acknowledge (timeout). */
int periph_addr_write(struct periph *p, uint8_t v);
int periph_addr_read(struct periph *p, uint8_t *v);
int periph_data_write(struct periph *p, uint8_t v);
int periph_data_read(struct periph *p, uint8_t *v);
void periph_control(struct periph *p, uint8_t v);
void periph_spp_data(struct periph *p, uint8_t v);
uint32_t periph_hm2_get(const struct periph *p, uint32_t addr);
void periph_hm2_set(struct periph *p, uint32_t addr, uint32_t v);

/* PC port registers in front of a peripheral.  The timeout bit is sticky;
 * while it is set no cycle reaches the peripheral (reads give 0xFF).
 * clear_on_one: writing 1 to bit 0 clears it, else writing 0 clears it. */
struct pcport {
    struct periph *p;
    int timeout;
    int clear_on_one;
    uint8_t ecr;
    int ecr_writes;
    /* instruction log: "outb(04,+2) inb(+1) outl(11223344,+4) ..." */
    char log[65536];
    size_t log_len;
    int log_on;
};
void pcport_init(struct pcport *pc, struct periph *p);
uint8_t pcport_in8(struct pcport *pc, int off);
void pcport_out8(struct pcport *pc, int off, uint8_t v);

/* Raw port-instruction layer over a pcport at `base` (ECR at base_hi+2). */
struct fake_raw {
    struct pcport *pc;
    unsigned long base, base_hi;
    int ioperm_fail;
    int ioperm_calls;
    unsigned long last_from, last_num;
    int perm_on;
    int wide_broken; /* inl returns 0xFFFFFFFF without bus cycles */
};
struct epp_raw_io fake_raw_io(struct fake_raw *f);

/* A batching epp backend directly on a pcport (the shape of the virtual
 * board's backend: everything happens at flush). */
int fake_batch_open(epp_port_t *port, struct pcport *pc, int wide);
extern int fake_batch_executes;

/* ppdev system calls over a pcport. */
struct fake_ppdev {
    struct pcport *pc;
    int open_fail, claim_fail, mode_fail;
    int mode;
    int flags;
    int claimed, released, closed;
    char calls[8192];
    size_t calls_len;
};
struct epp_ppdev_sys fake_ppdev_sys(struct fake_ppdev *f);

/* GPIO lines whose far end is the EPP peripheral, pin level: the
 * peripheral reacts to strobe edges and answers on nWait. */
struct fake_lines {
    struct periph *p;
    int level[EPP_GPIO_NLINES]; /* host-driven levels */
    int bus_out;                /* host drives D0..D7 */
    uint8_t bus_host;           /* what the host drives */
    uint8_t bus_periph;         /* what the peripheral drives on reads */
    int nwait;                  /* peripheral's nWait level */
    int pending_ack;            /* cycles polled before the ack shows */
    int ack_delay;              /* polls before acknowledging */
    int bus_conflicts;          /* host drove while the peripheral did */
    uint64_t t;                 /* fake clock, +50 ns per line access */
    int set_calls;
    int closed;
};
struct epp_gpio_lines fake_gpio_lines(struct fake_lines *f, int has_ninit);

#endif /* EPP_FAKES_H */
