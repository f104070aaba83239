/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Printed names of functions and pins (facts: spec §6, §7). */
#include <stdio.h>

#include "hm2/hm2.h"

const char *hm2_get_general_function_name(int gtag)
{
    switch (gtag) {
    case HM2_GTAG_WATCHDOG: return "Watchdog";
    case HM2_GTAG_IOPORT: return "IOPort";
    case HM2_GTAG_ENCODER: return "Encoder";
    case HM2_GTAG_STEPGEN: return "StepGen";
    case HM2_GTAG_PWMGEN: return "PWMGen";
    case HM2_GTAG_SSI: return "SSI Encoder";
    case HM2_GTAG_UART_TX: return "UART Transmit Channel";
    case HM2_GTAG_UART_RX: return "UART Receive Channel";
    case HM2_GTAG_TRAM: return "TranslationRAM";
    case HM2_GTAG_MUXED_ENCODER: return "Muxed Encoder";
    case HM2_GTAG_MUXED_ENCODER_SEL: return "Muxed Encoder Select";
    case HM2_GTAG_BSPI: return "Buffered SPI Interface";
    case HM2_GTAG_TPPWM: return "ThreePhasePWM";
    case HM2_GTAG_BISS: return "BiSS Encoder";
    case HM2_GTAG_FABS: return "Fanuc Abs Encoder";
    case HM2_GTAG_HM2DPLL: return "Hostmot2 DPLL";
    case HM2_GTAG_PKTUART_TX: return "PktUART Transmit Channel";
    case HM2_GTAG_PKTUART_RX: return "PktUART Receive Channel";
    case HM2_GTAG_INMUX: return "InMux Input Mux";
    case HM2_GTAG_INM: return "InM Input Module";
    case HM2_GTAG_XY2MOD: return "xy2mod Galvo interface";
    case HM2_GTAG_RCPWMGEN: return "RCPWMGen";
    case HM2_GTAG_OUTM: return "OutM Output Module";
    case HM2_GTAG_LED: return "LED";
    case HM2_GTAG_RESOLVER: return "Resolver";
    case HM2_GTAG_SMARTSERIAL: return "Smart Serial Interface";
    case HM2_GTAG_SSR: return "SSR";
    case HM2_GTAG_SMARTSERIALB: return "Smart Serial Interface";
    case HM2_GTAG_ONESHOT: return "OneShot";
    default: return NULL;
    }
}

const char *hm2_gtag_name(int gtag, char *buf, size_t len)
{
    const char *name = hm2_get_general_function_name(gtag);
    if (name)
        return name;
    snprintf(buf, len, "(unknown-gtag-%d)", gtag);
    return buf;
}

const char *hm2_get_hal_module_name(int gtag)
{
    switch (gtag) {
    case HM2_GTAG_ENCODER:
    case HM2_GTAG_MUXED_ENCODER:
    case HM2_GTAG_MUXED_ENCODER_SEL: return "encoder";
    case HM2_GTAG_STEPGEN: return "stepgen";
    case HM2_GTAG_PWMGEN: return "pwmgen";
    case HM2_GTAG_TPPWM: return "3pwmgen";
    case HM2_GTAG_RCPWMGEN: return "rcpwmgen";
    case HM2_GTAG_SSI: return "ssi";
    case HM2_GTAG_BSPI: return "bspi";
    case HM2_GTAG_UART_TX:
    case HM2_GTAG_UART_RX: return "uart";
    case HM2_GTAG_SMARTSERIAL:
    case HM2_GTAG_SMARTSERIALB: return "sserial";
    default: return NULL;
    }
}

static const char *encoder_pin(int p, bool muxed)
{
    static const char *plain[] = {NULL, "A", "B", "Index", "IndexMask", "Probe", "Shared Index"};
    static const char *mux[] = {NULL, "Muxed A", "Muxed B", "Muxed Index", "Muxed IndexMask",
                                "Muxed Probe", "Muxed Shared Index"};
    if (p < 1 || p > 6)
        return NULL;
    return muxed ? mux[p] : plain[p];
}

const char *hm2_get_pin_secondary_name(const struct hm2_pin *pin, char *buf, size_t len)
{
    int p = pin->sec_pin & 0x7F;
    const char *name = NULL;

    switch (pin->sec_tag) {
    case HM2_GTAG_ENCODER: name = encoder_pin(p, false); break;
    case HM2_GTAG_MUXED_ENCODER: name = encoder_pin(p, true); break;
    case HM2_GTAG_MUXED_ENCODER_SEL:
        if (p == 1) name = "Mux Select 0";
        else if (p == 2) name = "Mux Select 1";
        break;
    case HM2_GTAG_STEPGEN:
        if (pin->unused) name = "(unused)";
        else if (p == 1) name = "Step";
        else if (p == 2) name = "Direction";
        else if (p >= 3 && p <= 8) {
            snprintf(buf, len, "Table%dPin", p - 1);
            return buf;
        } else if (p == 9) name = "Index";
        else if (p == 10) name = "Probe";
        break;
    case HM2_GTAG_PWMGEN:
        if (p == 1) name = "Out0 (PWM or Up)";
        else if (p == 2) name = "Out1 (Dir or Down)";
        else if (p == 3) name = "Not-Enable";
        break;
    case HM2_GTAG_SSI:
        if (p == 1) name = "Clock";
        else if (p == 2) name = "ClockEnable";
        else if (p == 3) name = "Data";
        break;
    case HM2_GTAG_UART_TX:
        if (p == 1) name = "TX Data";
        else if (p == 2) name = "Drv Enable";
        break;
    case HM2_GTAG_UART_RX:
        if (p == 1) name = "RX Data";
        break;
    case HM2_GTAG_TPPWM: {
        static const char *t[] = {NULL, "PWM A", "PWM B", "PWM C", "PWM /A",
                                  "PWM /B", "PWM /C", "Enable", "Fault"};
        if (p >= 1 && p <= 8) name = t[p];
        break;
    }
    case HM2_GTAG_SMARTSERIAL:
    case HM2_GTAG_SMARTSERIALB:
        if (p >= 1 && p <= 8) snprintf(buf, len, "%s%d", (pin->sec_pin & 0x80) ? "tx" : "rx", p - 1);
        else if (p >= 0x11 && p <= 0x18) snprintf(buf, len, "txen%d", p - 0x11);
        else break;
        return buf;
    default: break;
    }
    if (name)
        return name;
    snprintf(buf, len, "unknown-pin-%d", p);
    return buf;
}

const char *hm2_get_pin_secondary_hal_name(const struct hm2_pin *pin)
{
    static const char *table[] = {"table2", "table3", "table4", "table5", "table6", "table7"};
    int p = pin->sec_pin & 0x7F;
    switch (pin->sec_tag) {
    case HM2_GTAG_ENCODER:
    case HM2_GTAG_MUXED_ENCODER: {
        static const char *e[] = {NULL, "phase-A", "phase-B", "phase-Z", "phase-Z-mask",
                                  "probe-latch", "shared-Z"};
        return (p >= 1 && p <= 6) ? e[p] : NULL;
    }
    case HM2_GTAG_MUXED_ENCODER_SEL: return p == 1 ? "sel0" : p == 2 ? "sel1" : NULL;
    case HM2_GTAG_STEPGEN:
        if (p == 1) return "step";
        if (p == 2) return "direction";
        if (p >= 3 && p <= 8) return table[p - 3];
        if (p == 9) return "index";
        if (p == 10) return "probe";
        return NULL;
    case HM2_GTAG_PWMGEN:
        return p == 1 ? "out0" : p == 2 ? "out1" : p == 3 ? "enable" : NULL;
    default: return NULL;
    }
}
