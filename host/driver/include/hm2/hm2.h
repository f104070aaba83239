/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2.h - the hostmot2 core: board state, IDROM, module and pin
 * descriptors, config string, pin allocation, module drivers.
 *
 * Two layers share these types:
 *  - the probe layer (libhm2core, no HAL calls): hm2_probe() reads and
 *    validates the IDROM over an llio, parses the config string, the module
 *    and pin descriptors, allocates pins and can print the pin report.  The
 *    hm2pinout tool and the unit tests use it alone.
 *  - the HAL layer (hostmot2.so): hm2_register() = hm2_probe() + HAL export
 *    + the per-period read/write functions.
 * Board state is malloc'd per board and freed on unregister; what HAL must
 * see (pin pointers, parameter storage) is hal_malloc'd.
 */
#ifndef HM2_HM2_H
#define HM2_HM2_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "hal.h"
#include "hm2/bitfile.h"
#include "hm2/llio.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HM2_VERSION "0.15"

/* ---- register map constants (spec §1-§3) ---- */
#define HM2_ADDR_IOCOOKIE 0x0100
#define HM2_ADDR_CONFIGNAME 0x0104
#define HM2_ADDR_IDROM_OFFSET 0x010C
#define HM2_IOCOOKIE 0x55AACAFEu
#define HM2_CONFIGNAME "HOSTMOT2"
#define HM2_CONFIGNAME_LEN 8
#define HM2_ADDR_SPACE 0x10000u
#define HM2_IDROM_HEADER_SIZE 64
#define HM2_MAX_MODULE_DESCRIPTORS 48
#define HM2_MD_SIZE 12
#define HM2_MAX_IO_WIDTH 1000
#define HM2_MIN_CLOCK 1000000u

/* ---- GTags (spec §6) ---- */
enum {
    HM2_GTAG_NONE = 0,
    HM2_GTAG_IRQ = 1,
    HM2_GTAG_WATCHDOG = 2,
    HM2_GTAG_IOPORT = 3,
    HM2_GTAG_ENCODER = 4,
    HM2_GTAG_STEPGEN = 5,
    HM2_GTAG_PWMGEN = 6,
    HM2_GTAG_SPI = 7,
    HM2_GTAG_SSI = 8,
    HM2_GTAG_UART_TX = 9,
    HM2_GTAG_UART_RX = 10,
    HM2_GTAG_TRAM = 11,
    HM2_GTAG_MUXED_ENCODER = 12,
    HM2_GTAG_MUXED_ENCODER_SEL = 13,
    HM2_GTAG_BSPI = 14,
    HM2_GTAG_TPPWM = 19,
    HM2_GTAG_BISS = 24,
    HM2_GTAG_FABS = 25,
    HM2_GTAG_HM2DPLL = 26,
    HM2_GTAG_PKTUART_TX = 27,
    HM2_GTAG_PKTUART_RX = 28,
    HM2_GTAG_INMUX = 30,
    HM2_GTAG_INM = 35,
    HM2_GTAG_XY2MOD = 43,
    HM2_GTAG_RCPWMGEN = 44,
    HM2_GTAG_OUTM = 45,
    HM2_GTAG_LED = 128,
    HM2_GTAG_RESOLVER = 192,
    HM2_GTAG_SMARTSERIAL = 193,
    HM2_GTAG_SSR = 195,
    HM2_GTAG_SMARTSERIALB = 198,
    HM2_GTAG_ONESHOT = 199,
};

/* ---- messages ----
 * Levels follow RTAPI: PRINT is unconditional (rtapi_print), the others go
 * through rtapi_print_msg at that level. */
enum hm2_level {
    HM2_PRINT = 0,
    HM2_ERR = 1,
    HM2_WARN = 2,
    HM2_INFO = 3,
    HM2_DBG = 4,
};
/* Receives one complete message line (no trailing newline). */
typedef void (*hm2_log_fn)(void *ctx, int level, const char *line);

/* ---- config string (spec §12) ---- */
#define HM2_MAX_SSERIAL_PORTS 4
#define HM2_MAX_ABS_CHANNELS 32
struct hm2_config {
    char firmware[HM2_FIRMWARE_NAME_MAX + 1];
    int num_encoders, num_pwmgens, num_3pwmgens, num_rcpwmgens, num_stepgens;
    int num_leds, num_bspis, num_uarts, num_pktuarts, num_resolvers, num_dplls;
    int num_inmuxs, num_inms, num_outms, num_xy2mods, num_ssrs, num_oneshots;
    int num_sserials;
    /* -1: not given (seed behaviour: every stepgen pin stays with its
     * stepgen, the ones past Step/Direction are reported "(unused)");
     * N >= 1: LinuxCNC 2.9 behaviour, pins past N become GPIO. */
    int stepgen_width;
    int enable_raw;
    char sserial_modes[HM2_MAX_SSERIAL_PORTS][9];
};

/* Smart Serial channel mode from sserial_port_N: '0'..'9', or 'x' for a
 * channel left to GPIO (a channel the string does not reach: '0'). */
char hm2_sserial_mode(const struct hm2_config *cfg, int port, int chan);

void hm2_config_defaults(struct hm2_config *cfg);
/* Parse `str` (may be NULL or empty).  0 or -EINVAL with the LinuxCNC
 * message in err. */
int hm2_config_parse(const char *str, struct hm2_config *cfg, char *err, size_t errlen);

/* ---- IDROM / descriptors ---- */
struct hm2_idrom {
    uint32_t idrom_type;
    uint32_t offset_to_modules;
    uint32_t offset_to_pin_desc;
    char board_name[9]; /* 8 raw bytes + NUL */
    uint32_t fpga_size;
    uint32_t fpga_pins;
    uint32_t io_ports;
    uint32_t io_width;
    uint32_t port_width;
    uint32_t clock_low;
    uint32_t clock_high;
    uint32_t instance_stride_0;
    uint32_t instance_stride_1;
    uint32_t register_stride_0;
    uint32_t register_stride_1;
};

struct hm2_md {
    uint8_t gtag, version, clock_tag, instances;
    uint16_t base_address;
    uint8_t num_registers;
    uint8_t strides; /* raw byte */
    uint32_t register_stride;
    uint32_t instance_stride;
    uint32_t multiple_registers;
    uint32_t clock_freq;
    uint16_t addr; /* where the record sits in the register space */
};

/* Pin directions as the report prints them. */
enum { HM2_PIN_DIR_INPUT = 1, HM2_PIN_DIR_OUTPUT = 2 };

struct hm2_gpio_hal;
struct hm2_pin {
    /* from the pin descriptor */
    uint8_t sec_pin, sec_tag, sec_unit, primary_tag;
    int port_num, port_pin;
    /* allocation: gtag = IOPort (full GPIO) or the module that owns it */
    int gtag;
    int direction;
    bool unused; /* owned by a stepgen but past Step/Direction (seed) */
    struct hm2_gpio_hal *hal;
};

/* Supported modules: which MD, how many instances exist and are used. */
struct hm2_module {
    bool present;
    int md_index;
    struct hm2_md md;
    int available;
    int used;
};

struct hostmot2;
typedef struct hostmot2 hostmot2_t;

/* Debug switches (hostmot2 modparams). */
struct hm2_debug {
    int idrom, module_descriptors, pin_descriptors, modules;
};
/* Load options: debug switches and the firmware search path (NULL: the
 * default, see hm2_firmware_default_path()). */
struct hm2_options {
    struct hm2_debug debug;
    const char *firmware_path;
};

/* ---- per-module runtime state (HAL layer) ---- */
struct hm2_ioport_state;
struct hm2_watchdog_state;
struct hm2_encoder_state;
struct hm2_stepgen_state;
struct hm2_pwmgen_state;
struct hm2_led_state;
struct hm2_sserial_state;
struct hm2_raw_state;
struct hm2_tram;

struct hostmot2 {
    hm2_llio_t *llio;
    hm2_log_fn log;
    void *log_ctx;
    struct hm2_debug debug;
    struct hm2_config config;

    uint32_t idrom_offset;
    struct hm2_idrom idrom;
    struct hm2_md md[HM2_MAX_MODULE_DESCRIPTORS];
    int num_mds;
    struct hm2_pin *pin;
    int num_pins;

    struct hm2_module watchdog, ioport, encoder, muxed_encoder, stepgen, pwmgen, led, sserial;
    int num_leds;

    /* HAL layer (NULL in a probe-only board) */
    struct hm2_tram *tram;
    struct hm2_ioport_state *ioport_s;
    struct hm2_watchdog_state *watchdog_s;
    struct hm2_encoder_state *encoder_s;
    struct hm2_stepgen_state *stepgen_s;
    struct hm2_pwmgen_state *pwmgen_s;
    struct hm2_led_state *led_s;
    struct hm2_sserial_state *sserial_s;
    struct hm2_raw_state *raw_s;
    hal_bit_t *io_error; /* param storage, hal_malloc'd */
    bool needs_reset;
    bool read_requested; /* <pfx>.read-request sent this period's reads */
    bool registered;
    void *handle; /* struct hm2_funct_handle (HAL memory), see hostmot2.c */
};

/* ---- messages ---- */
void hm2_msg(const hostmot2_t *hm2, int level, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* Message without the board prefix ("hm2: ..."). */
void hm2_msg_core(hm2_log_fn log, void *ctx, int level, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* A formatted line to log (no prefix added); nothing when log is NULL.
 * The board drivers' (llio providers') messages go through this. */
void hm2_log_printf(hm2_log_fn log, void *ctx, int level, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* ---- probe layer (no HAL) ---- */
/* Parse config, load firmware if asked, read and validate everything,
 * allocate pins.  Returns a malloc'd board or NULL (and *err = -errno)
 * after printing why.  No HAL object is created. */
hostmot2_t *hm2_probe(hm2_llio_t *llio, const char *config, const struct hm2_options *opts,
                      hm2_log_fn log, void *log_ctx, int *err);
void hm2_free(hostmot2_t *hm2);

/* Steps of hm2_probe, exposed for tests. */
int hm2_load_firmware(hostmot2_t *hm2, const char *search_path);
int hm2_read_idrom(hostmot2_t *hm2);
int hm2_read_pin_descriptors(hostmot2_t *hm2);
int hm2_read_module_descriptors(hostmot2_t *hm2);
int hm2_parse_module_descriptors(hostmot2_t *hm2);
int hm2_allocate_pins(hostmot2_t *hm2);
void hm2_print_pin_usage(const hostmot2_t *hm2);
void hm2_print_idrom(const hostmot2_t *hm2);
void hm2_print_modules(const hostmot2_t *hm2);

/* Names (spec §6, §7). */
const char *hm2_get_general_function_name(int gtag);
/* The name, or "(unknown-gtag-N)" written to buf. */
const char *hm2_gtag_name(int gtag, char *buf, size_t len);
const char *hm2_get_pin_secondary_name(const struct hm2_pin *pin, char *buf, size_t len);
/* HAL alias stem of a module output pin ("step", "out0", ...), NULL if none. */
const char *hm2_get_pin_secondary_hal_name(const struct hm2_pin *pin);
/* "encoder", "stepgen", "pwmgen", ... for HAL names; NULL if unknown. */
const char *hm2_get_hal_module_name(int gtag);

/* Register address of (module md, register reg, instance inst). */
static inline uint32_t hm2_reg_addr(const struct hm2_md *md, int reg, int inst)
{
    return (uint32_t)md->base_address + (uint32_t)reg * md->register_stride +
           (uint32_t)inst * md->instance_stride;
}

/* Register access helpers that report failures with a message. */
int hm2_read_reg(hostmot2_t *hm2, uint32_t addr, uint32_t *val);
int hm2_write_reg(hostmot2_t *hm2, uint32_t addr, uint32_t val);

/* ---- pure maths (spec §10), exposed for tests ---- */
/* StepGen */
uint32_t hm2_stepgen_ns_to_clocks(uint32_t ns, uint32_t clock_low, bool *clipped);
double hm2_stepgen_clocks_to_ns(uint32_t clocks, uint32_t clock_low);
double hm2_stepgen_physical_maxvel(uint32_t steplen_ns, uint32_t stepspace_ns, double scale);
uint32_t hm2_stepgen_rate_register(double vel, double scale, uint32_t clock_low);
struct hm2_stepgen_posctl {
    /* inputs */
    double position_cmd, position_fb, velocity_fb, maxaccel, period_s;
    double old_position_cmd;
    /* outputs (the dbg_* pins) */
    double dbg_pos_minus_prev_cmd, dbg_ff_vel, dbg_vel_error, dbg_s_to_match,
        dbg_err_at_match;
};
double hm2_stepgen_position_control(struct hm2_stepgen_posctl *p);
double hm2_stepgen_velocity_control(double velocity_cmd, double velocity_fb, double maxaccel,
                                    double period_s);
/* Feedback: accumulate a new 16.16 accumulator reading into subcounts. */
int64_t hm2_stepgen_accumulate(int64_t subcounts, uint32_t prev_acc, uint32_t acc);

/* Encoder */
uint32_t hm2_encoder_tsdiv(uint32_t clock_low, bool hires);
double hm2_encoder_seconds_per_tsc(uint32_t clock_low, uint32_t tsdiv);
uint32_t hm2_encoder_qfilter_rate(uint32_t clock_low, uint32_t sample_frequency,
                                  uint32_t *effective_frequency);
int32_t hm2_wrap16(int32_t diff);

/* Encoder count/velocity tracker, one per instance. */
enum { HM2_ENCODER_STOPPED = 0, HM2_ENCODER_MOVING = 1 };
struct hm2_encoder_track {
    int state;
    uint16_t prev_reg_count;
    int32_t rawcounts;
    int32_t zero_offset;
    int32_t rawlatch;
    int32_t prev_event_rawcounts;
    uint16_t prev_event_reg_timestamp;
    uint16_t prev_time_of_interest;
    int32_t tsc_num_rollovers;
    int32_t prev_dS_counts;
    double velocity;
    bool latch_pending; /* LatchOnIndex written 1, waiting for the event */
    bool probe_pending;
};
struct hm2_encoder_sample {
    uint32_t count_reg; /* Count+Timestamp register */
    uint32_t ccr;       /* Latch/Control register */
    uint16_t tscount;   /* TSCount register */
};
/* Returns 1 when an index event happened (caller clears index-enable). */
int hm2_encoder_track_update(struct hm2_encoder_track *t, const struct hm2_encoder_sample *s,
                             double scale, double seconds_per_tsc, double vel_timeout,
                             bool *probe_event);

/* PWMGen */
struct hm2_pwm_rate {
    int bits;
    uint32_t dds;
    uint32_t frequency; /* possibly clipped */
    bool clipped;
};
struct hm2_pwm_rate hm2_pwmgen_pwm_rate(uint32_t pwm_frequency, uint32_t clock_high);
uint32_t hm2_pwmgen_pdm_rate(uint32_t pdm_frequency, uint32_t clock_high, int *clip);
uint32_t hm2_pwmgen_mode_word(int output_type, int pwm_bits, bool dither, bool *bad_type);
uint32_t hm2_pwmgen_value_register(double value, double scale, bool enable, int output_type,
                                   int pwm_bits, bool offset_mode, bool dither);

/* Watchdog */
uint32_t hm2_watchdog_timer_value(uint32_t timeout_ns, uint32_t clock_low, bool *clipped);
uint32_t hm2_watchdog_max_timeout_ns(uint32_t clock_low);

#ifdef __cplusplus
}
#endif

#endif /* HM2_HM2_H */
