/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Pin allocation (spec §10.5) and the load-time pin report (spec §14). */
#include <errno.h>
#include <stdio.h>

#include "hm2/hm2.h"

/* How many units of a secondary function are enabled, i.e. which pins the
 * module instance takes. */
static int units_enabled(const hostmot2_t *hm2, int sec_tag)
{
    switch (sec_tag) {
    case HM2_GTAG_ENCODER: return hm2->encoder.used;
    case HM2_GTAG_MUXED_ENCODER: return (hm2->muxed_encoder.used + 1) / 2;
    case HM2_GTAG_MUXED_ENCODER_SEL: return hm2->muxed_encoder.used > 0 ? 0x7F : 0;
    case HM2_GTAG_STEPGEN: return hm2->stepgen.used;
    case HM2_GTAG_PWMGEN: return hm2->pwmgen.used;
    case HM2_GTAG_SMARTSERIAL: return hm2->sserial.used;
    default: return 0; /* modules this driver does not run keep their pins GPIO */
    }
}

int hm2_allocate_pins(hostmot2_t *hm2)
{
    if (hm2->num_pins > 0 && !hm2->ioport.present) {
        for (int i = 0; i < hm2->num_pins; i++)
            hm2_msg(hm2, HM2_ERR, "hm2_set_pin_source: invalid pin number %d", i);
        hm2_msg(hm2, HM2_ERR,
                "IDROM lists %d I/O pins but the firmware has no IOPort module (inconsistent "
                "firmware), aborting driver load",
                hm2->num_pins);
        return -EINVAL;
    }
    for (int i = 0; i < hm2->num_pins; i++) {
        struct hm2_pin *p = &hm2->pin[i];
        p->gtag = HM2_GTAG_IOPORT;
        p->direction = HM2_PIN_DIR_INPUT;
        p->unused = false;
        if (p->sec_tag == 0)
            continue;
        int units = units_enabled(hm2, p->sec_tag);
        if (units <= 0)
            continue;
        if (!(p->sec_unit & 0x80) && p->sec_unit >= units)
            continue;
        if (p->sec_tag == HM2_GTAG_SMARTSERIAL &&
            hm2_sserial_mode(&hm2->config, p->sec_unit & 0x7F, (p->sec_pin & 0x0F) - 1) == 'x')
            continue; /* sserial_port_N=..x..: the channel's pins stay GPIO */
        if (p->sec_tag == HM2_GTAG_STEPGEN) {
            int sp = p->sec_pin & 0x7F;
            int width = hm2->config.stepgen_width;
            if (width >= 1 && sp > width)
                continue; /* LinuxCNC 2.9: extra stepgen pins become GPIO */
            if (width < 1 && sp >= 3 && sp <= 8)
                p->unused = true; /* seed: kept by the stepgen, reported unused */
        }
        p->gtag = p->sec_tag;
        p->direction = (p->sec_pin & 0x80) ? HM2_PIN_DIR_OUTPUT : HM2_PIN_DIR_INPUT;
    }
    return 0;
}

void hm2_print_pin_usage(const hostmot2_t *hm2)
{
    hm2_msg(hm2, HM2_PRINT, "%d I/O Pins used:", hm2->num_pins);
    for (int i = 0; i < hm2->num_pins; i++) {
        const struct hm2_pin *p = &hm2->pin[i];
        char cbuf[64], nbuf[32];
        const char *conn = hm2_llio_pin_name(hm2->llio, i, cbuf, sizeof(cbuf));
        if (!conn)
            continue;
        if (p->gtag == HM2_GTAG_IOPORT) {
            hm2_msg(hm2, HM2_PRINT, "    IO Pin %03d (%s): IOPort", i, conn);
            continue;
        }
        const char *fn = hm2_get_general_function_name(p->gtag);
        const char *pn = hm2_get_pin_secondary_name(p, nbuf, sizeof(nbuf));
        const char *dir = p->direction == HM2_PIN_DIR_OUTPUT ? "Output" : "Input";
        if (p->sec_unit & 0x80)
            hm2_msg(hm2, HM2_PRINT, "    IO Pin %03d (%s): %s (all), pin %s (%s)", i, conn, fn, pn,
                    dir);
        else
            hm2_msg(hm2, HM2_PRINT, "    IO Pin %03d (%s): %s #%d, pin %s (%s)", i, conn, fn,
                    p->sec_unit, pn, dir);
    }
}

void hm2_print_modules(const hostmot2_t *hm2)
{
    hm2_msg(hm2, HM2_PRINT, "HM2 Modules used:");
    hm2_msg(hm2, HM2_PRINT, "IO Ports: %d", hm2->ioport.used);
    if (hm2->encoder.present)
        hm2_msg(hm2, HM2_PRINT, "Encoders: %d", hm2->encoder.used);
    if (hm2->muxed_encoder.present)
        hm2_msg(hm2, HM2_PRINT, "Muxed Encoders: %d", hm2->muxed_encoder.used);
    if (hm2->pwmgen.present)
        hm2_msg(hm2, HM2_PRINT, "PWMGen: %d", hm2->pwmgen.used);
    if (hm2->stepgen.present)
        hm2_msg(hm2, HM2_PRINT, "StepGen: %d", hm2->stepgen.used);
    if (hm2->sserial.present)
        hm2_msg(hm2, HM2_PRINT, "Smart Serial ports: %d", hm2->sserial.used);
    hm2_msg(hm2, HM2_PRINT, "Watchdog: %d", hm2->watchdog.used);
    if (hm2->led.present)
        hm2_msg(hm2, HM2_PRINT, "LEDs: %d", hm2->num_leds);
}
