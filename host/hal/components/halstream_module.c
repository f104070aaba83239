/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * halstream_module.c - what the realtime ends of the FIFOs (sampler and
 * streamer) share beyond the ring itself: checking their cfg=/depth= module
 * parameters, moving values between HAL pins and FIFO records, and waiting
 * for the userspace peer under the simulated clock.  See halstream.h.
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
