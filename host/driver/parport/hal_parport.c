/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hal_parport - HAL driver for PC parallel ports (docs/hal_parport.md).
 *
 *   loadrt hal_parport cfg="ADDR [in|out|epp|x] [ADDR [TYPE] ...]"
 *
 * Per port p (numbered from 0 in cfg order), as LinuxCNC 2.9:
 *   bit IN  parport.p.pin-NN-out               each output pin
 *   bit OUT parport.p.pin-NN-in, -in-not       each input pin
 *   bit RW  parport.p.pin-NN-out-invert, -out-reset
 *   u32 RW  parport.p.reset-time (ns), debug1, debug2
 *   functions parport.p.read, .write, .reset; parport.read-all, .write-all
 * Pins by type: out/epp: 1-9, 14, 16, 17 out, 10-13, 15 in; in: 1, 14, 16,
 * 17 out, 2-13, 15 in; x: 2-9 out, 1, 10-17 in.
 *
 * The realtime functions work on the port's three registers (pp_port.h)
 * whatever the backend; the register bits that the port inverts are
 * inverted back so that a TRUE -out pin is a high pin and a high pin is a
 * TRUE -in pin.  Everything is checked and opened before anything is
 * created in HAL, and a failure undoes it all.
 */
#include <errno.h>
#include <string.h>

#include "hal.h"
#include "pp_cfg.h"
#include "pp_port.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("HAL driver for PC parallel ports");

static char *cfg = "";
RTAPI_MP_STRING(cfg, "ports: ADDR [in|out|epp|x] ... (docs/hal_parport.md)");

#define NPINS 18 /* index = DB-25 pin number, 1..17 */

struct hp_port {
    struct pp_port port;
    int index;
    uint32_t out_mask, in_mask; /* bit n = pin n */
    hal_bit_t *out[NPINS];
    hal_bit_t *in[NPINS], *in_not[NPINS];
    hal_bit_t out_invert[NPINS], out_reset[NPINS];
    hal_u32_t reset_time, debug1, debug2;
    uint8_t data, control;   /* as last written by write */
    long long write_time;    /* rtapi_get_time() of the last write */
    int io_error;            /* an I/O error was reported */
};

struct hp_state {
    int n;
    struct hp_port *port[PP_MAX_PORTS];
};

static int comp_id;
static struct hp_state *state; /* in HAL memory; for rtapi_app_exit */

static const int control_pin[4] = {1, 14, 16, 17}; /* control bits 0..3 */
static const int control_inverted[4] = {1, 1, 0, 1};

static uint32_t range(int from, int to)
{
    uint32_t m = 0;
    for (int p = from; p <= to; p++)
        m |= 1u << p;
    return m;
}

static void pin_sets(enum pp_mode mode, uint32_t *out, uint32_t *in)
{
    const uint32_t data = range(2, 9), status = range(10, 13) | (1u << 15);
    const uint32_t control = (1u << 1) | (1u << 14) | (1u << 16) | (1u << 17);
    switch (mode) {
    case PP_MODE_IN:
        *out = control;
        *in = data | status;
        break;
    case PP_MODE_X:
        *out = data;
        *in = control | status;
        break;
    default:
        *out = data | control;
        *in = status;
        break;
    }
}

static void io_failed(struct hp_port *hp, const char *what, int r)
{
    if (hp->io_error)
        return;
    hp->io_error = 1;
    rtapi_print_msg(RTAPI_MSG_ERR, "hal_parport: port %d (%s): %s failed: %s (reported once)\n",
                    hp->index, hp->port.name, what, strerror(-r));
}

/* ---- realtime functions ------------------------------------------------- */

static inline int level_of(struct hp_port *hp, int pin)
{
    return (*hp->out[pin] ? 1 : 0) ^ (hp->out_invert[pin] ? 1 : 0);
}

static void port_read(struct hp_port *hp)
{
    struct pp_port *p = &hp->port;
    uint8_t s = 0, v = 0;
    int r = p->ops->begin(p);
    if (!r)
        r = p->ops->read_status(p, &s);
    if (r) {
        io_failed(hp, "read", r);
        return;
    }
    int lv[NPINS] = {0};
    lv[10] = (s >> 6) & 1;
    lv[11] = !((s >> 7) & 1);
    lv[12] = (s >> 5) & 1;
    lv[13] = (s >> 4) & 1;
    lv[15] = (s >> 3) & 1;
    if (p->mode == PP_MODE_IN) {
        r = p->ops->read_data(p, &v);
        for (int i = 0; i < 8; i++)
            lv[i + 2] = (v >> i) & 1;
    } else if (p->mode == PP_MODE_X) {
        r = p->ops->read_control(p, &v);
        for (int i = 0; i < 4; i++)
            lv[control_pin[i]] = ((v >> i) & 1) ^ control_inverted[i];
    }
    if (r) {
        io_failed(hp, "read", r);
        return;
    }
    for (int pin = 1; pin < NPINS; pin++)
        if (hp->in_mask & (1u << pin)) {
            *hp->in[pin] = lv[pin];
            *hp->in_not[pin] = !lv[pin];
        }
}

static uint8_t control_value(struct hp_port *hp, const int *lv)
{
    if (hp->port.mode == PP_MODE_X)
        return PP_CTRL_RELEASED;
    uint8_t c = hp->port.mode == PP_MODE_IN ? PP_CTRL_DIR : 0u;
    for (int i = 0; i < 4; i++)
        c |= (uint8_t)((lv[control_pin[i]] ^ control_inverted[i]) << i);
    return c;
}

static void port_write(struct hp_port *hp)
{
    struct pp_port *p = &hp->port;
    int lv[NPINS] = {0};
    for (int pin = 1; pin < NPINS; pin++)
        if (hp->out_mask & (1u << pin))
            lv[pin] = level_of(hp, pin);
    uint8_t d = 0;
    for (int i = 0; i < 8; i++)
        d |= (uint8_t)(lv[i + 2] << i);
    uint8_t c = control_value(hp, lv);
    int r = p->ops->begin(p);
    if (!r && p->mode != PP_MODE_IN)
        r = p->ops->write_data(p, d);
    if (!r)
        r = p->ops->write_control(p, c);
    hp->data = d;
    hp->control = c;
    hp->write_time = rtapi_get_time();
    if (r)
        io_failed(hp, "write", r);
}

/* Reset: pins with -out-reset go back to their inactive level (the level
 * of a FALSE -out pin, i.e. -out-invert), reset-time after the write. */
static void port_reset(struct hp_port *hp, long period)
{
    struct pp_port *p = &hp->port;
    int any = 0;
    /* as LinuxCNC 2.9: reset-time is limited to a quarter period */
    if (period > 0 && hp->reset_time > (hal_u32_t)(period / 4))
        hp->reset_time = (hal_u32_t)(period / 4);
    for (int pin = 1; pin < NPINS; pin++)
        if ((hp->out_mask & (1u << pin)) && hp->out_reset[pin])
            any = 1;
    if (!any)
        return;
    uint8_t d = hp->data, c = hp->control;
    for (int i = 0; i < 8; i++) {
        int pin = i + 2;
        if ((hp->out_mask & (1u << pin)) && hp->out_reset[pin])
            d = (uint8_t)((d & ~(1u << i)) | ((hp->out_invert[pin] ? 1u : 0u) << i));
    }
    if (p->mode != PP_MODE_X)
        for (int i = 0; i < 4; i++) {
            int pin = control_pin[i];
            if (!hp->out_reset[pin])
                continue;
            unsigned bit = (hp->out_invert[pin] ? 1u : 0u) ^ (unsigned)control_inverted[i];
            c = (uint8_t)((c & ~(1u << i)) | (bit << i));
        }
    long long deadline = hp->write_time + (long long)hp->reset_time;
    if (rtapi_is_simclock())
        p->stamp_floor = deadline; /* no time passes in a function: stamp it */
    else
        while (rtapi_get_time() < deadline)
            ;
    int r = p->ops->begin(p);
    if (!r && d != hp->data && p->mode != PP_MODE_IN)
        r = p->ops->write_data(p, d);
    if (!r && c != hp->control)
        r = p->ops->write_control(p, c);
    p->stamp_floor = 0;
    if (r)
        io_failed(hp, "reset", r);
}

static void fn_read(void *arg, long period)
{
    (void)period;
    port_read(arg);
}

static void fn_write(void *arg, long period)
{
    (void)period;
    port_write(arg);
}

static void fn_reset(void *arg, long period)
{
    port_reset(arg, period);
}

static void fn_read_all(void *arg, long period)
{
    (void)period;
    struct hp_state *st = arg;
    for (int i = 0; i < st->n; i++)
        port_read(st->port[i]);
}

static void fn_write_all(void *arg, long period)
{
    (void)period;
    struct hp_state *st = arg;
    for (int i = 0; i < st->n; i++)
        port_write(st->port[i]);
}

/* ---- loading ------------------------------------------------------------ */

static int export_port(struct hp_port *hp)
{
    int i = hp->index, r = 0;
    for (int pin = 1; pin < NPINS && !r; pin++) {
        if (hp->out_mask & (1u << pin)) {
            r = hal_pin_bit_newf(HAL_IN, &hp->out[pin], comp_id, "parport.%d.pin-%02d-out", i,
                                 pin);
            if (!r)
                r = hal_param_bit_newf(HAL_RW, &hp->out_invert[pin], comp_id,
                                       "parport.%d.pin-%02d-out-invert", i, pin);
            if (!r)
                r = hal_param_bit_newf(HAL_RW, &hp->out_reset[pin], comp_id,
                                       "parport.%d.pin-%02d-out-reset", i, pin);
        } else if (hp->in_mask & (1u << pin)) {
            r = hal_pin_bit_newf(HAL_OUT, &hp->in[pin], comp_id, "parport.%d.pin-%02d-in", i,
                                 pin);
            if (!r)
                r = hal_pin_bit_newf(HAL_OUT, &hp->in_not[pin], comp_id,
                                     "parport.%d.pin-%02d-in-not", i, pin);
        }
    }
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &hp->reset_time, comp_id, "parport.%d.reset-time", i);
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &hp->debug1, comp_id, "parport.%d.debug1", i);
    if (!r)
        r = hal_param_u32_newf(HAL_RW, &hp->debug2, comp_id, "parport.%d.debug2", i);
    if (!r)
        r = hal_export_functf(fn_read, hp, 0, 0, comp_id, "parport.%d.read", i);
    if (!r)
        r = hal_export_functf(fn_write, hp, 0, 0, comp_id, "parport.%d.write", i);
    if (!r)
        r = hal_export_functf(fn_reset, hp, 0, 0, comp_id, "parport.%d.reset", i);
    return r;
}

static void close_ports(struct hp_state *st)
{
    for (int i = 0; i < st->n; i++)
        if (st->port[i])
            pp_close(&st->port[i]->port);
    st->n = 0;
}

static int open_ports(struct hp_state *st, const struct pp_cfg *c)
{
    char err[600];
    for (int i = 0; i < c->n; i++) {
        struct hp_port *hp = hal_malloc(sizeof(*hp));
        if (!hp) {
            rtapi_print_msg(RTAPI_MSG_ERR, "hal_parport: out of HAL memory\n");
            return -ENOMEM;
        }
        memset(hp, 0, sizeof(*hp));
        hp->index = i;
        int r = pp_open(&hp->port, &c->port[i], &pp_sys_linux, rtapi_get_time, err, sizeof(err));
        if (r) {
            rtapi_print_msg(RTAPI_MSG_ERR, "hal_parport: port %d ('%s'): %s\n", i,
                            c->port[i].text, err);
            return r;
        }
        st->port[st->n++] = hp;
        if (hp->port.note[0])
            rtapi_print_msg(RTAPI_MSG_INFO, "hal_parport: %s\n", hp->port.note);
        pin_sets(c->port[i].mode, &hp->out_mask, &hp->in_mask);
        rtapi_print_msg(RTAPI_MSG_DBG, "hal_parport: port %d: %s (%s), type %s\n", i,
                        hp->port.name, hp->port.kind, pp_mode_name(c->port[i].mode));
    }
    return 0;
}

int rtapi_app_main(void)
{
    struct pp_cfg c;
    char err[600];
    int r = pp_cfg_parse(cfg, &c, err, sizeof(err));
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hal_parport: %s\n", err);
        return r;
    }
    comp_id = hal_init("hal_parport");
    if (comp_id < 0)
        return comp_id;
    state = hal_malloc(sizeof(*state));
    if (!state) {
        r = -ENOMEM;
        goto fail;
    }
    memset(state, 0, sizeof(*state));
    r = open_ports(state, &c);
    if (r)
        goto fail;
    for (int i = 0; i < state->n && !r; i++)
        r = export_port(state->port[i]);
    if (!r)
        r = hal_export_funct("parport.read-all", fn_read_all, state, 0, 0, comp_id);
    if (!r)
        r = hal_export_funct("parport.write-all", fn_write_all, state, 0, 0, comp_id);
    if (r)
        goto fail;
    hal_ready(comp_id);
    return 0;
fail:
    if (state)
        close_ports(state);
    state = NULL;
    hal_exit(comp_id);
    return r;
}

void rtapi_app_exit(void)
{
    if (state)
        close_ports(state);
    state = NULL;
    hal_exit(comp_id);
}
