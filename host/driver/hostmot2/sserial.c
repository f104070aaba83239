/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * sserial.c - Smart Serial ports (GTag 0xC1, hm2_sserial.v): discovery at
 * load, process data every servo period, fault counting (docs/sserial.md).
 *
 * Load: per port, write each enabled channel's mode (sserial_port_N) to its
 * CS register, start those channels in normal mode (the firmware discovers
 * the remotes), wait for the command to finish and read what answered:
 * name, unit number and process-data sizes.  Every answering remote of a
 * known type gets its HAL objects (hm2_<board>.<n>.<type>.<port>.<chan>.*).
 *
 * Every period: read() takes the Command, Data, CS and Interface registers
 * of the last doit (TRAM), write() puts the outputs into the Interface
 * registers and issues the next doit (TRAM, after them).  A failed or
 * unfinished doit adds fault-inc to the port's error count, a good one
 * takes fault-dec off; past fault-lim the port stops (pins keep their last
 * values) until its run pin goes false and true again.
 */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sserial.h"

enum ss_state { SS_STOPPED, SS_STARTING, SS_RUNNING, SS_FAULTED };

struct ss_port_hal {
    hal_bit_t *run;
    hal_u32_t *run_state, *error_count;
    hal_u32_t fault_inc, fault_dec, fault_lim;
};

struct ss_port {
    int index, nchan;
    uint32_t mask; /* channels with a remote */
    struct ss_chan ch[SS_MAX_CHANNELS];
    struct ss_port_hal *hal;
    uint32_t *rd_cmd, *rd_data, *wr_cmd;
    enum ss_state state;
    bool cmd_sent; /* the last write issued a doit / start */
    bool prev_run;
    uint32_t count;
};

struct hm2_sserial_state {
    int num;
    struct ss_port *port;
};

static const struct ss_remote_type *const remote_types[] = {&hm2_ss_7i76, &hm2_ss_7i77};

#define WAIT_STEP_NS 20000L
#define WAIT_STEPS 250 /* 5 ms: discovery of 8 channels takes < 1 ms */

/* ---- load time --------------------------------------------------------- */

static void wait_ns(hostmot2_t *hm2, long ns)
{
    if (hm2->llio->delay) {
        hm2->llio->delay(hm2->llio, ns);
        return;
    }
    struct timespec ts = {0, ns};
    nanosleep(&ts, NULL);
}

static uint32_t reg(const hostmot2_t *hm2, int r, const struct ss_port *p, int chan)
{
    return hm2_reg_addr(&hm2->sserial.md, r, p->index) + 4u * (uint32_t)chan;
}

/* Run a port command to its end; *data = the Data register after it. */
static int run_command(hostmot2_t *hm2, struct ss_port *p, uint32_t cmd, uint32_t *data)
{
    uint32_t v = 0;
    int r = hm2_write_reg(hm2, reg(hm2, SS_REG_CMD, p, 0), cmd);
    for (int i = 0; !r && i < WAIT_STEPS; i++) {
        wait_ns(hm2, WAIT_STEP_NS);
        if ((r = hm2_read_reg(hm2, reg(hm2, SS_REG_CMD, p, 0), &v)))
            break;
        if (v == 0)
            return hm2_read_reg(hm2, reg(hm2, SS_REG_DATA, p, 0), data);
    }
    if (!r) {
        hm2_msg(hm2, HM2_WARN,
                "Smart Serial port %d: command 0x%04X did not finish within %ld us (command "
                "register still 0x%04X)",
                p->index, cmd, WAIT_STEPS * WAIT_STEP_NS / 1000, v);
        r = -ETIMEDOUT;
    }
    return r;
}

static const struct ss_remote_type *find_type(const char *name)
{
    for (size_t i = 0; i < sizeof(remote_types) / sizeof(remote_types[0]); i++)
        if (strcmp(remote_types[i]->name, name) == 0)
            return remote_types[i];
    return NULL;
}

/* What answered on channel c of a started port. */
static int identify(hostmot2_t *hm2, struct ss_port *p, int c)
{
    struct ss_chan *ch = &p->ch[c];
    uint32_t nm = 0, cs = 0;
    int r;
    if ((r = hm2_read_reg(hm2, reg(hm2, SS_REG_IF0, p, c), &nm)) ||
        (r = hm2_read_reg(hm2, reg(hm2, SS_REG_IF0 + 1, p, c), &ch->unit)) ||
        (r = hm2_read_reg(hm2, reg(hm2, SS_REG_CS, p, c), &cs)))
        return r;
    char name[5];
    for (int k = 0; k < 4; k++) {
        unsigned char b = (unsigned char)(nm >> (8 * k));
        name[k] = isprint(b) ? (char)tolower(b) : '?';
    }
    name[4] = '\0';
    ch->in_bits = (int)((cs >> 16) & 0xFF);
    ch->out_bits = (int)(cs >> 24);
    ch->type = find_type(name);
    if (!ch->type) {
        hm2_msg(hm2, HM2_ERR,
                "Smart Serial port %d channel %d: remote '%s' (unit 0x%08X) is not a board "
                "this driver knows (known: 7i76, 7i77); channel not used",
                p->index, c, name, ch->unit);
        return 0;
    }
    hm2_msg(hm2, HM2_PRINT,
            "Smart Serial port %d channel %d: found %s (unit 0x%08X) in mode %d, %d bits in, "
            "%d bits out",
            p->index, c, name, ch->unit, ch->mode, ch->in_bits, ch->out_bits);
    p->mask |= 1u << c;
    return 0;
}

/* Start every enabled channel of port p and see who answers. */
static int discover(hostmot2_t *hm2, struct ss_port *p)
{
    uint32_t n = 0, fail = 0, want = 0;
    int r = run_command(hm2, p, SS_CMD_READ_LOCAL | 0u, &n);
    if (r)
        return r == -ETIMEDOUT ? 0 : r;
    p->nchan = (int)(n < SS_MAX_CHANNELS ? n : SS_MAX_CHANNELS);
    for (int c = 0; c < p->nchan; c++) {
        char m = hm2_sserial_mode(&hm2->config, p->index, c);
        p->ch[c].port = p->index;
        p->ch[c].chan = c;
        if (m == 'x')
            continue;
        p->ch[c].mode = m - '0';
        want |= 1u << c;
        if ((r = hm2_write_reg(hm2, reg(hm2, SS_REG_CS, p, c), (uint32_t)p->ch[c].mode)))
            return r;
    }
    if (!want)
        return 0;
    if ((r = hm2_ioport_early_outputs(hm2, HM2_GTAG_SMARTSERIAL))) {
        hm2_msg(hm2, HM2_ERR, "Smart Serial port %d: cannot enable the TxData pins", p->index);
        return r;
    }
    if ((r = run_command(hm2, p, SS_CMD_START_NORMAL | want, &fail))) {
        if (r != -ETIMEDOUT)
            return r;
        /* the board's clock does not run while the driver waits (an
         * Ethernet board that runs only per datagram): no remotes */
        hm2_msg(hm2, HM2_WARN, "Smart Serial port %d: discovery did not finish; port not used",
                p->index);
        return 0;
    }
    for (int c = 0; c < p->nchan; c++) {
        if (!(want & (1u << c)))
            continue;
        if (fail & (1u << c)) {
            hm2_msg(hm2, HM2_INFO,
                    "Smart Serial port %d channel %d: no remote answered in mode %d; channel "
                    "not used",
                    p->index, c, p->ch[c].mode);
            continue;
        }
        if ((r = identify(hm2, p, c)))
            return r;
    }
    /* channels that answered with an unknown board stay stopped */
    uint32_t stray = want & ~fail & ~p->mask;
    if (stray)
        return run_command(hm2, p, SS_CMD_STOP | stray, &fail);
    return 0;
}

static int port_hal(hostmot2_t *hm2, struct ss_port *p)
{
    int id = hm2->llio->comp_id, r;
    const char *b = hm2->llio->name;
    char pfx[HM2_LLIO_NAME_LEN + 32];
    snprintf(pfx, sizeof(pfx), "%s.sserial.port-%d", b, p->index);
    p->hal = hm2_hal_zalloc(hm2, sizeof(*p->hal), "sserial port pins");
    if (!p->hal)
        return -ENOMEM;
    struct ss_port_hal *h = p->hal;
    if ((r = hal_pin_bit_newf(HAL_IN, &h->run, id, "%s.run", pfx)) ||
        (r = hal_pin_u32_newf(HAL_OUT, &h->run_state, id, "%s.run_state", pfx)) ||
        (r = hal_pin_u32_newf(HAL_OUT, &h->error_count, id, "%s.error-count", pfx)) ||
        (r = hal_param_u32_newf(HAL_RW, &h->fault_inc, id, "%s.fault-inc", pfx)) ||
        (r = hal_param_u32_newf(HAL_RW, &h->fault_dec, id, "%s.fault-dec", pfx)) ||
        (r = hal_param_u32_newf(HAL_RW, &h->fault_lim, id, "%s.fault-lim", pfx)))
        return hm2_hal_fail(hm2, r, "sserial port");
    *h->run = 1;
    *h->run_state = 0;
    *h->error_count = 0;
    h->fault_inc = 10;
    h->fault_dec = 1;
    h->fault_lim = 200;
    for (int c = 0; c < p->nchan; c++) {
        struct ss_chan *ch = &p->ch[c];
        if (!(p->mask & (1u << c)))
            continue;
        char rp[HM2_LLIO_NAME_LEN + 32];
        snprintf(rp, sizeof(rp), "%s.%s.%d.%d", b, ch->type->name, p->index, c);
        if ((r = ch->type->setup(hm2, ch, rp)))
            return r;
    }
    return 0;
}

static int port_tram(hostmot2_t *hm2, struct ss_port *p)
{
    int r;
    if ((r = hm2_tram_add_read(hm2, reg(hm2, SS_REG_CMD, p, 0), &p->rd_cmd, 1)) ||
        (r = hm2_tram_add_read(hm2, reg(hm2, SS_REG_DATA, p, 0), &p->rd_data, 1)))
        return r;
    for (int c = 0; c < p->nchan; c++) {
        struct ss_chan *ch = &p->ch[c];
        if (!(p->mask & (1u << c)))
            continue;
        if ((r = hm2_tram_add_read(hm2, reg(hm2, SS_REG_CS, p, c), &ch->rd_cs, 1)))
            return r;
        for (int k = 0; k < 3; k++)
            if ((r = hm2_tram_add_read(hm2, reg(hm2, SS_REG_IF0 + k, p, c), &ch->rd_if[k], 1)) ||
                (r = hm2_tram_add_write(hm2, reg(hm2, SS_REG_IF0 + k, p, c), &ch->wr_if[k], 1)))
                return r;
    }
    /* after the interface registers: the doit sees this period's outputs */
    return hm2_tram_add_write(hm2, reg(hm2, SS_REG_CMD, p, 0), &p->wr_cmd, 1);
}

static int sserial_setup(hostmot2_t *hm2)
{
    if (!hm2->sserial.present || hm2->sserial.used <= 0)
        return 0;
    struct hm2_sserial_state *s = calloc(1, sizeof(*s));
    if (!s) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating Smart Serial state");
        return -ENOMEM;
    }
    hm2->sserial_s = s;
    s->num = hm2->sserial.used;
    s->port = calloc((size_t)s->num, sizeof(*s->port));
    if (!s->port) {
        hm2_msg(hm2, HM2_ERR, "out of memory allocating Smart Serial ports");
        return -ENOMEM;
    }
    for (int i = 0; i < s->num; i++) {
        struct ss_port *p = &s->port[i];
        int r;
        p->index = i;
        if ((r = discover(hm2, p)) || (r = port_hal(hm2, p)) || (r = port_tram(hm2, p)))
            return r;
        p->state = p->mask ? SS_RUNNING : SS_STOPPED;
        *p->hal->run_state = p->mask ? 0x03u : 0x00u;
        p->prev_run = true;
    }
    return 0;
}

/* ---- every period ------------------------------------------------------- */

static const char *why(uint32_t cs)
{
    uint32_t e = (cs >> 8) & 0x1F;
    return e & 0x01   ? "no answer (remote unplugged or not powered?)"
           : e & 0x02 ? "CRC error"
           : e & 0x04 ? "framing error"
           : e & 0x08 ? "answer cut short"
           : e & 0x10 ? "channel not running"
                      : "failed";
}

static void fault(hostmot2_t *hm2, struct ss_port *p, const char *what, int chan)
{
    struct ss_port_hal *h = p->hal;
    p->count += h->fault_inc;
    if (p->count <= h->fault_lim)
        return;
    p->state = SS_FAULTED;
    if (chan >= 0)
        hm2_msg(hm2, HM2_ERR,
                "Smart Serial port %d channel %d (%s): %s; error count %u > fault-lim %u: port "
                "%d stopped, its pins keep their last values (toggle %s.sserial.port-%d.run "
                "to restart)",
                p->index, chan, p->ch[chan].type->name, what, p->count, h->fault_lim, p->index,
                hm2->llio->name, p->index);
    else
        hm2_msg(hm2, HM2_ERR,
                "Smart Serial port %d: %s; error count %u > fault-lim %u: port stopped (toggle "
                "%s.sserial.port-%d.run to restart)",
                p->index, what, p->count, h->fault_lim, hm2->llio->name, p->index);
}

static void read_running(hostmot2_t *hm2, struct ss_port *p)
{
    if (*p->rd_cmd != 0) {
        fault(hm2, p, "process data exchange still running at the next read (servo period too "
                      "short?)", -1);
        return;
    }
    bool bad = false;
    for (int c = 0; c < p->nchan && p->state == SS_RUNNING; c++) {
        struct ss_chan *ch = &p->ch[c];
        if (!(p->mask & (1u << c)))
            continue;
        if (*p->rd_data & (1u << c)) {
            bad = true;
            fault(hm2, p, why(*ch->rd_cs), c);
            continue;
        }
        uint32_t in[3] = {*ch->rd_if[0], *ch->rd_if[1], *ch->rd_if[2]};
        ch->type->unpack(ch, in);
    }
    if (!bad)
        p->count = p->count > p->hal->fault_dec ? p->count - p->hal->fault_dec : 0;
}

static void read_starting(hostmot2_t *hm2, struct ss_port *p)
{
    if (*p->rd_cmd != 0)
        return; /* discovery still running: look again next period */
    p->cmd_sent = false;
    uint32_t fail = *p->rd_data & p->mask;
    if (fail) {
        for (int c = 0; c < p->nchan; c++)
            if (fail & (1u << c))
                hm2_msg(hm2, HM2_ERR,
                        "Smart Serial port %d channel %d (%s): restart failed: %s; port stays "
                        "stopped",
                        p->index, c, p->ch[c].type->name, why(*p->ch[c].rd_cs));
        p->state = SS_FAULTED;
        return;
    }
    p->state = SS_RUNNING;
    p->count = 0;
    hm2_msg(hm2, HM2_INFO, "Smart Serial port %d: running again", p->index);
}

static void sserial_process_read(hostmot2_t *hm2, long period)
{
    struct hm2_sserial_state *s = hm2->sserial_s;
    (void)period;
    if (!s)
        return;
    for (int i = 0; i < s->num; i++) {
        struct ss_port *p = &s->port[i];
        if (!p->cmd_sent)
            continue;
        if (p->state == SS_RUNNING)
            read_running(hm2, p);
        else if (p->state == SS_STARTING)
            read_starting(hm2, p);
    }
}

static uint32_t run_state(enum ss_state st)
{
    return st == SS_RUNNING ? 0x03u : st == SS_STARTING ? 0x01u : 0x00u;
}

static void sserial_prepare_write(hostmot2_t *hm2, long period)
{
    struct hm2_sserial_state *s = hm2->sserial_s;
    /* no doit at load: the first read() would come before it could end */
    if (!s || period == HM2_LOAD_PERIOD)
        return;
    for (int i = 0; i < s->num; i++) {
        struct ss_port *p = &s->port[i];
        bool run = *p->hal->run != 0;
        uint32_t cmd = 0;
        if (!run && p->state != SS_STOPPED) {
            cmd = SS_CMD_STOP | p->mask;
            p->state = SS_STOPPED;
        } else if (run && !p->prev_run && p->mask &&
                   (p->state == SS_STOPPED || p->state == SS_FAULTED)) {
            cmd = SS_CMD_START_NORMAL | p->mask;
            p->state = SS_STARTING;
        } else if (p->state == SS_RUNNING) {
            for (int c = 0; c < p->nchan; c++) {
                struct ss_chan *ch = &p->ch[c];
                if (!(p->mask & (1u << c)))
                    continue;
                uint32_t out[3];
                ch->type->pack(ch, out);
                for (int k = 0; k < 3; k++)
                    *ch->wr_if[k] = out[k];
            }
            cmd = SS_CMD_DOIT | p->mask;
        } else if (p->state == SS_FAULTED && p->cmd_sent) {
            cmd = SS_CMD_STOP | p->mask; /* once, right after the fault */
        }
        /* a 0 write is no command: the firmware ignores it */
        if ((cmd & SS_CMD_DOIT) || (cmd & 0xFF00u) == SS_CMD_START_NORMAL)
            p->cmd_sent = true; /* read() looks at its result */
        else if (p->state != SS_STARTING)
            p->cmd_sent = false;
        *p->wr_cmd = cmd;
        p->prev_run = run;
        *p->hal->run_state = run_state(p->state);
        *p->hal->error_count = p->count;
    }
}

static void sserial_cleanup(hostmot2_t *hm2)
{
    struct hm2_sserial_state *s = hm2->sserial_s;
    if (!s)
        return;
    free(s->port);
    free(s);
    hm2->sserial_s = NULL;
}

const struct hm2_module_ops hm2_sserial_ops = {
    .name = "sserial",
    .setup = sserial_setup,
    .process_read = sserial_process_read,
    .prepare_write = sserial_prepare_write,
    .cleanup = sserial_cleanup,
};
