/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * pluto_drivers.h - the per-period logic of pluto_servo and pluto_step
 * (spec/pluto.md §4, §6, §9), separate from the HAL glue so the unit tests
 * can run it with plain memory behind the pin pointers.  The structs live
 * in HAL shared memory in the real modules.
 */
#ifndef PLUTO_DRIVERS_H
#define PLUTO_DRIVERS_H

#include <stdint.h>

#include "hal.h"
#include "pluto_common.h"

#ifdef __cplusplus
extern "C" {
#endif

struct pluto_servo {
    /* pins */
    hal_s32_t *enc_count[4];
    hal_float_t *enc_position[4];
    hal_float_t *enc_velocity[4];
    hal_bit_t *enc_reset[4];
    hal_bit_t *enc_index_enable[4];
    hal_float_t *pwm_value[4];
    hal_bit_t *pwm_enable[4];
    hal_bit_t *dout[20];
    hal_bit_t *din[20];
    hal_bit_t *din_not[20];
    /* parameters */
    hal_float_t enc_scale[4];
    hal_bit_t z_polarity;
    hal_float_t pwm_offset[4];
    hal_float_t pwm_scale[4];
    hal_float_t pwm_max_dc[4];
    hal_float_t pwm_min_dc[4];
    hal_bit_t pwm_pwmdir[4];
    hal_bit_t is_pdm;
    hal_bit_t dout_invert[20];
    hal_u32_t communication_error;
    hal_s32_t debug_0;
    hal_s32_t debug_1;
    /* state */
    int64_t last_count[4];
    int64_t last_index[4];
    int64_t reset_count[4];
    /* load-time settings */
    int watchdog;
    int test_encoder;
    epp_port_t *port;
    struct pluto_log log;
    uint8_t rbuf[20];
    uint8_t status;
};

struct pluto_step {
    hal_float_t *position_cmd[4];
    hal_float_t *velocity_fb[4];
    hal_float_t *position_fb[4];
    hal_s32_t *counts[4];
    hal_bit_t *enable[4];
    hal_bit_t *reset[4];
    hal_bit_t *dout[14];
    hal_bit_t *din[16];
    hal_bit_t *din_not[16];
    hal_float_t scale[4];
    hal_float_t maxvel[4];
    hal_bit_t step_polarity;
    hal_u32_t steplen;
    hal_u32_t stepspace;
    hal_u32_t dirtime;
    hal_bit_t dout_invert[14];
    hal_u32_t communication_error;
    hal_s32_t debug_0;
    hal_s32_t debug_1;
    hal_float_t debug_2;
    hal_float_t debug_3;
    int64_t last_count[4];
    int64_t reset_count[4];
    double old_position_cmd[4];
    double old_velocity_cmd[4];
    int maxvel_msg_printed[4];
    int speedrange;
    int watchdog;
    epp_port_t *port;
    struct pluto_log log;
    uint8_t rbuf[20];
    uint8_t status;
};

/* Parameter defaults (spec tables §4.4, §6.4); pins are left alone. */
void pluto_servo_defaults(struct pluto_servo *s);
void pluto_step_defaults(struct pluto_step *s);

/* The HAL functions' bodies.  period in ns. */
void pluto_servo_read(struct pluto_servo *s, long period);
void pluto_servo_write(struct pluto_servo *s, long period);
void pluto_step_read(struct pluto_step *s, long period);
void pluto_step_write(struct pluto_step *s, long period);

/* Pure encodings, exposed for the tests. */
uint16_t pluto_servo_pwm_word(struct pluto_servo *s, int ch);
uint16_t pluto_servo_control_word(const struct pluto_servo *s);
/* Ticks of 1.6 us for a time in ns, clamped to 31 (LinuxCNC truncates). */
int pluto_step_ticks(uint32_t ns);
uint16_t pluto_step_timing_word(const struct pluto_step *s);
uint16_t pluto_step_dout_word(const struct pluto_step *s);

#ifdef __cplusplus
}
#endif

#endif /* PLUTO_DRIVERS_H */
