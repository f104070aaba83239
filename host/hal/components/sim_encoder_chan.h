/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * sim_encoder_chan.h - one channel of the sim_encoder component
 * (sim_encoder.comp): its HAL pins and its phase accumulator.  A header
 * because the .comp's instance structure holds an array of these.
 */
#ifndef HM_SIM_ENCODER_CHAN_H
#define HM_SIM_ENCODER_CHAN_H

#include <stdint.h>
#include "hal.h"

typedef struct {
    hal_bit_t *phase_a, *phase_b, *phase_z;
    hal_u32_t *ppr;
    hal_s32_t *rawcounts;
    hal_float_t *scale, *speed;
    double last_scale, inv_scale; /* scale as last seen, and 1 / scale */
    int32_t increment;            /* phase step per make-pulses period */
    uint32_t phase;               /* a quadrature step each time bit 31 changes */
    int quad;                     /* quadrature state 0..3 */
    int pulse;                    /* pulse within the revolution, 0..ppr-1 */
} se_chan_t;

#endif /* HM_SIM_ENCODER_CHAN_H */
