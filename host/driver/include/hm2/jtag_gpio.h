/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * jtag_gpio.h - a JTAG cable bit-banged on four GPIO lines (TCK, TMS, TDI
 * outputs, TDO input), e.g. a Raspberry Pi header wired to a board's JTAG
 * connector.  Per bit: TCK low, TMS and TDI set, TDO sampled (the TAP
 * drives it after the previous falling edge), TCK high (the TAP samples
 * TMS/TDI on this rising edge).
 *
 * The line layer is separate so that the engine runs on libgpiod lines
 * (jtag_gpiod_lines_open) or on a test's model of the wire.
 */
#ifndef HM2_JTAG_GPIO_H
#define HM2_JTAG_GPIO_H

#include <stddef.h>
#include <stdint.h>

#include "hm2/jtag.h"

#ifdef __cplusplus
extern "C" {
#endif

enum jtag_gpio_role { JTAG_GPIO_TCK, JTAG_GPIO_TMS, JTAG_GPIO_TDI, JTAG_GPIO_TDO, JTAG_GPIO_N };

struct jtag_gpio_lines {
    int (*set)(void *ctx, int role, int level);
    int (*get)(void *ctx, int role, int *level);
    void (*close)(void *ctx);
    void *ctx;
};

struct jtag_gpio {
    struct jtag_gpio_lines lines;
    uint64_t tck;
    char err[256];
};

void jtag_gpio_init(struct jtag_gpio *g, const struct jtag_gpio_lines *lines);
struct jtag_cable jtag_gpio_cable(struct jtag_gpio *g);

/* libgpiod lines from "CHIP:TCK/TMS/TDI/TDO" (gpiod_linespec syntax, e.g.
 * "gpiochip0:11/25/10/9").  0, or -errno with the reason in err. */
int jtag_gpiod_lines_open(struct jtag_gpio_lines *lines, const char *spec, char *err,
                          size_t errlen);

#ifdef __cplusplus
}
#endif

#endif /* HM2_JTAG_GPIO_H */
