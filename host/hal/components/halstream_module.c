/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halstream_module.c - what the realtime ends of the FIFOs (sampler and
 * streamer) share beyond the ring itself: checking their cfg=/depth= module
 * parameters, creating and removing their channels, moving values between
 * HAL pins and FIFO records, and waiting for the userspace peer under the
 * simulated clock.  See halstream.h.
 */
#include <errno.h>
#include <string.h>

#include "halstream.h"
#include "rtapi.h"

static int count_strings(char *const *a, int max)
{
    int n = 0;
    while (n < max && a[n] != NULL && a[n][0] != '\0')
        n++;
    return n;
}

int halstream_check_params(const char *who, char *const *cfg, const int *depth, int max_chan,
                           hal_type_t (*types)[HALSTREAM_MAX_PINS], int *npins)
{
    char err[256];
    int nchan = count_strings(cfg, max_chan);
    if (nchan == 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: no channels specified (cfg= missing)\n", who);
        return -EINVAL;
    }
    for (int n = nchan; n < max_chan; n++) {
        if (cfg[n] != NULL && cfg[n][0] != '\0') {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: cfg string %d is empty\n", who, nchan);
            return -EINVAL;
        }
        if (depth[n] != 0) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "%s: ERROR: depth given for channel %d but only %d cfg string(s)\n",
                            who, n, nchan);
            return -EINVAL;
        }
    }
    for (int n = 0; n < nchan; n++) {
        if (depth[n] <= 0) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "%s: ERROR: channel %d (cfg=%s): depth missing or not positive "
                            "(%d)\n",
                            who, n, cfg[n], depth[n]);
            return -EINVAL;
        }
        npins[n] = halstream_parse_cfg(cfg[n], types[n], err, sizeof(err));
        if (npins[n] < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: channel %d: bad cfg '%s': %s\n", who, n,
                            cfg[n], err);
            return -EINVAL;
        }
    }
    return nchan;
}

void halstream_from_pin(hal_type_t type, const void *pin, halstream_value_t *v)
{
    memset(v, 0, sizeof(*v));
    switch (type) {
    case HAL_BIT:
        v->b = *(const hal_bit_t *)pin;
        break;
    case HAL_FLOAT:
        v->f = *(const hal_float_t *)pin;
        break;
    case HAL_S32:
        v->s = *(const hal_s32_t *)pin;
        break;
    case HAL_U32:
        v->u = *(const hal_u32_t *)pin;
        break;
    case HAL_S64:
        v->ls = *(const hal_s64_t *)pin;
        break;
    case HAL_U64:
        v->lu = *(const hal_u64_t *)pin;
        break;
    default:
        break;
    }
}

void halstream_to_pin(hal_type_t type, void *pin, const halstream_value_t *v)
{
    switch (type) {
    case HAL_BIT:
        *(hal_bit_t *)pin = v->b != 0;
        break;
    case HAL_FLOAT:
        *(hal_float_t *)pin = v->f;
        break;
    case HAL_S32:
        *(hal_s32_t *)pin = v->s;
        break;
    case HAL_U32:
        *(hal_u32_t *)pin = v->u;
        break;
    case HAL_S64:
        *(hal_s64_t *)pin = v->ls;
        break;
    case HAL_U64:
        *(hal_u64_t *)pin = v->lu;
        break;
    default:
        break;
    }
}

int halstream_wait_peer(halstream_t *s, int want_space)
{
    unsigned spins = 0;
    for (;;) {
        int fill = halstream_fill(s);
        if (want_space ? fill < halstream_capacity(s) : fill > 0)
            return 1;
        /* a peer that is not (or no longer) there never blocks us */
        if ((spins++ % 64) == 0 && !halstream_peer_attached(s))
            return 0;
        if (rtapi_sim_yield())
            return 0;
    }
}

static int init_channel(halstream_module_t *m, const halstream_module_desc_t *d, int n,
                        int depth, const hal_type_t *types, int npins)
{
    char err[256];
    halstream_chan_t *c = hal_malloc((long)d->chan_size);
    if (c == NULL) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: out of HAL memory for channel %d\n", d->who,
                        n);
        return -ENOMEM;
    }
    memset(c, 0, d->chan_size);
    int r;
    if ((r = hal_pin_bit_newf(HAL_IN, &c->enable, m->comp_id, "%s.%d.enable", d->name, n)) < 0 ||
        (r = hal_pin_s32_newf(HAL_OUT, &c->curr_depth, m->comp_id, "%s.%d.curr-depth", d->name,
                              n)) < 0)
        return r;
    *c->enable = 1;
    *c->curr_depth = 0;
    if ((r = d->export_pins(c, m->comp_id, n)) < 0)
        return r;
    c->npins = npins;
    for (int i = 0; i < npins; i++) {
        c->types[i] = types[i];
        r = hal_pin_newf(types[i], d->pin_dir, &c->pins[i], m->comp_id, "%s.%d.pin.%d", d->name,
                         n, i);
        if (r < 0)
            return r;
    }
    r = halstream_create(&c->fifo, d->name, n, depth, npins, types, err, sizeof(err));
    if (r < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: channel %d: %s\n", d->who, n, err);
        return r;
    }
    m->chans[n] = c;
    return hal_export_functf(d->funct, c, 1, 0, m->comp_id, "%s.%d", d->name, n);
}

static void destroy_channels(halstream_module_t *m)
{
    for (int i = 0; i < HALSTREAM_MAX_CHAN; i++) {
        if (m->chans[i] != NULL)
            halstream_destroy(&m->chans[i]->fifo);
        m->chans[i] = NULL;
    }
}

int halstream_module_load(halstream_module_t *m, const halstream_module_desc_t *d,
                          char *const *cfg, const int *depth)
{
    hal_type_t types[HALSTREAM_MAX_CHAN][HALSTREAM_MAX_PINS];
    int npins[HALSTREAM_MAX_CHAN];

    /* Validate everything before creating anything. */
    int nchan = halstream_check_params(d->who, cfg, depth, HALSTREAM_MAX_CHAN, types, npins);
    if (nchan < 0)
        return nchan;
    m->comp_id = hal_init(d->name);
    if (m->comp_id < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: ERROR: hal_init() failed\n", d->who);
        return m->comp_id;
    }
    for (int n = 0; n < nchan; n++) {
        int r = init_channel(m, d, n, depth[n], types[n], npins[n]);
        if (r < 0) {
            rtapi_print_msg(RTAPI_MSG_ERR,
                            "%s: ERROR: channel %d failed (%d), nothing of %s was kept\n",
                            d->who, n, r, d->name);
            destroy_channels(m);
            hal_exit(m->comp_id);
            return r;
        }
    }
    hal_ready(m->comp_id);
    return 0;
}

void halstream_module_unload(halstream_module_t *m)
{
    destroy_channels(m);
    hal_exit(m->comp_id);
}
