/* SPDX-License-Identifier: GPL-2.0-or-later */
/* Accepting module descriptors (spec §4 table, §11 step 6): IOPort first,
 * then the rest in table order; each supported module must match the
 * descriptor values the driver knows exactly, at most once. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "hm2/hm2.h"

enum md_msg_style { STYLE_GENERIC, STYLE_STEPGEN, STYLE_PWM, STYLE_ENCODER, STYLE_MUXED };

struct md_rule {
    int gtag;
    const uint8_t *versions;
    int num_versions;
    uint8_t num_registers;
    uint32_t instance_stride;
    uint32_t multiple_registers;
    enum md_msg_style style;
};

static const uint8_t v_zero[] = {0};
static const uint8_t v_encoder[] = {2, 3, 0x83};
static const uint8_t v_muxed[] = {2, 3, 4, 0x84};
static const uint8_t v_stepgen[] = {0, 1, 2, 0x42, 0xC2};
static const uint8_t v_pwm[] = {0, 1};

#define NV(a) (int)(sizeof(a) / sizeof((a)[0]))
static const struct md_rule rules[] = {
    {HM2_GTAG_WATCHDOG, v_zero, NV(v_zero), 3, 4, 0x00, STYLE_GENERIC},
    {HM2_GTAG_IOPORT, v_zero, NV(v_zero), 5, 4, 0x1F, STYLE_GENERIC},
    {HM2_GTAG_ENCODER, v_encoder, NV(v_encoder), 5, 4, 0x03, STYLE_ENCODER},
    {HM2_GTAG_MUXED_ENCODER, v_muxed, NV(v_muxed), 5, 4, 0x03, STYLE_MUXED},
    {HM2_GTAG_STEPGEN, v_stepgen, NV(v_stepgen), 10, 4, 0x1FF, STYLE_STEPGEN},
    {HM2_GTAG_PWMGEN, v_pwm, NV(v_pwm), 5, 4, 0x03, STYLE_PWM},
    {HM2_GTAG_LED, v_zero, NV(v_zero), 1, 4, 0x00, STYLE_GENERIC},
    {HM2_GTAG_SMARTSERIAL, v_zero, NV(v_zero), 6, 0x40, 0x3C, STYLE_GENERIC},
};
#undef NV

static const struct md_rule *find_rule(int gtag)
{
    for (size_t i = 0; i < sizeof(rules) / sizeof(rules[0]); i++)
        if (rules[i].gtag == gtag)
            return &rules[i];
    return NULL;
}

static struct hm2_module *module_slot(hostmot2_t *hm2, int gtag)
{
    switch (gtag) {
    case HM2_GTAG_WATCHDOG: return &hm2->watchdog;
    case HM2_GTAG_IOPORT: return &hm2->ioport;
    case HM2_GTAG_ENCODER: return &hm2->encoder;
    case HM2_GTAG_MUXED_ENCODER: return &hm2->muxed_encoder;
    case HM2_GTAG_STEPGEN: return &hm2->stepgen;
    case HM2_GTAG_PWMGEN: return &hm2->pwmgen;
    case HM2_GTAG_LED: return &hm2->led;
    case HM2_GTAG_SMARTSERIAL: return &hm2->sserial;
    default: return NULL;
    }
}

static bool version_ok(const struct md_rule *r, uint8_t v)
{
    for (int i = 0; i < r->num_versions; i++)
        if (r->versions[i] == v)
            return true;
    return false;
}

static int check_md(hostmot2_t *hm2, const struct hm2_md *md, const struct md_rule *r)
{
    if (version_ok(r, md->version) && md->num_registers == r->num_registers &&
        md->instance_stride == r->instance_stride &&
        md->multiple_registers == r->multiple_registers)
        return 0;
    const char *name = hm2_get_general_function_name(md->gtag);
    switch (r->style) {
    case STYLE_GENERIC:
        hm2_msg(hm2, HM2_ERR, "inconsistent Module Descriptor for %s, not loading driver", name);
        hm2_msg(hm2, HM2_ERR, "    Version = %d, expected %d", md->version, r->versions[0]);
        hm2_msg(hm2, HM2_ERR, "    NumRegisters = %d, expected %d", md->num_registers,
                r->num_registers);
        hm2_msg(hm2, HM2_ERR, "    InstanceStride = 0x%08X, expected 0x%08X", md->instance_stride,
                r->instance_stride);
        hm2_msg(hm2, HM2_ERR, "    MultipleRegisters = 0x%08X, expected 0x%08X",
                md->multiple_registers, r->multiple_registers);
        break;
    case STYLE_STEPGEN:
        hm2_msg(hm2, HM2_ERR, "unknown stepgen MD:");
        hm2_msg(hm2, HM2_ERR, "    Version = %d", md->version);
        hm2_msg(hm2, HM2_ERR, "    NumRegisters = %d", md->num_registers);
        hm2_msg(hm2, HM2_ERR, "    InstanceStride = 0x%08X", md->instance_stride);
        hm2_msg(hm2, HM2_ERR, "    MultipleRegisters = 0x%08X", md->multiple_registers);
        break;
    case STYLE_PWM:
        hm2_msg(hm2, HM2_ERR, "Unsupported PWM firmware version");
        break;
    case STYLE_ENCODER:
        hm2_msg(hm2, HM2_ERR, "inconsistent Encoder Module Descriptor!");
        break;
    case STYLE_MUXED:
        hm2_msg(hm2, HM2_ERR, "inconsistent Muxed Encoder Module Descriptor!");
        break;
    }
    return -EINVAL;
}

/* Every register of every instance must lie inside the register space. */
static int check_md_extent(hostmot2_t *hm2, int i, const struct hm2_md *md)
{
    if (md->instances == 0 || md->num_registers == 0)
        return 0;
    uint64_t last = (uint64_t)md->base_address +
                    (uint64_t)(md->num_registers - 1) * md->register_stride +
                    (uint64_t)(md->instances - 1) * md->instance_stride + 3;
    if (last < HM2_ADDR_SPACE)
        return 0;
    hm2_msg(hm2, HM2_ERR,
            "Module Descriptor %d (at 0x%04x): %s registers reach 0x%llX, past the 64 KiB "
            "register space (inconsistent firmware), aborting driver load",
            i, md->addr, hm2_get_general_function_name(md->gtag), (unsigned long long)last);
    return -EINVAL;
}

static int requested(const hostmot2_t *hm2, int gtag)
{
    switch (gtag) {
    case HM2_GTAG_ENCODER:
    case HM2_GTAG_MUXED_ENCODER: return hm2->config.num_encoders;
    case HM2_GTAG_STEPGEN: return hm2->config.num_stepgens;
    case HM2_GTAG_PWMGEN: return hm2->config.num_pwmgens;
    case HM2_GTAG_SMARTSERIAL: return hm2->config.num_sserials;
    default: return -1;
    }
}

static const char *count_key(int gtag)
{
    switch (gtag) {
    case HM2_GTAG_STEPGEN: return "num_stepgens";
    case HM2_GTAG_PWMGEN: return "num_pwmgens";
    case HM2_GTAG_SMARTSERIAL: return "num_sserials";
    default: return "num_encoders";
    }
}

static int accept_md(hostmot2_t *hm2, int i)
{
    const struct hm2_md *md = &hm2->md[i];
    const struct md_rule *rule = find_rule(md->gtag);
    const char *name = hm2_get_general_function_name(md->gtag);

    if (!rule) {
        char unk[32];
        if (!name)
            hm2_msg(hm2, HM2_WARN, "Firmware contains unknown function (gtag-%d)", md->gtag);
        hm2_msg(hm2, HM2_WARN, "MD %d: %dx %s v%d: ignored", i, md->instances,
                hm2_gtag_name(md->gtag, unk, sizeof(unk)), md->version);
        return 0;
    }
    struct hm2_module *m = module_slot(hm2, md->gtag);
    /* Plain and muxed encoders share one set of HAL encoder objects
     * (hm2_X.encoder.NN): LinuxCNC 2.9 treats the second kind as a duplicate. */
    const struct hm2_module *twin = md->gtag == HM2_GTAG_ENCODER         ? &hm2->muxed_encoder
                                    : md->gtag == HM2_GTAG_MUXED_ENCODER ? &hm2->encoder
                                                                          : NULL;
    if (m->present || (twin && twin->present)) {
        hm2_msg(hm2, HM2_ERR,
                "found duplicate Module Descriptor for %s (inconsistent firmware), not loading "
                "driver",
                name);
        return -EINVAL;
    }
    if (check_md(hm2, md, rule) || check_md_extent(hm2, i, md))
        return -EINVAL;
    if (md->gtag == HM2_GTAG_STEPGEN && md->version == 0xC2) {
        hm2_msg(hm2, HM2_ERR,
                "MD %d: StepGen v0xC2 (index/probe position latching) is not supported by this "
                "driver: its index-enable, probe-enable and position-latch pins cannot be "
                "created, not loading driver (use a firmware with StepGen v2 or v0x42)",
                i);
        return -EINVAL;
    }

    int used = md->instances;
    switch (md->gtag) {
    case HM2_GTAG_IOPORT:
        if (md->instances != hm2->idrom.io_ports) {
            hm2_msg(hm2, HM2_ERR,
                    "IDROM IOPorts is %d but MD IOPort NumInstances is %d, inconsistent "
                    "firmware, aborting driver load",
                    (int)hm2->idrom.io_ports, md->instances);
            return -EINVAL;
        }
        break;
    case HM2_GTAG_WATCHDOG:
        if (md->instances > 1)
            hm2_msg(hm2, HM2_WARN, "MD %d: %d watchdog instances, only the first is used", i,
                    md->instances);
        used = md->instances ? 1 : 0;
        break;
    case HM2_GTAG_LED: {
        int board = hm2->llio->num_leds;
        int want = hm2->config.num_leds;
        if (want < 0 || want == board) {
            hm2->num_leds = board;
        } else if (want > board) {
            hm2_msg(hm2, HM2_PRINT, "There are only %d LEDs on this board type, defaulting to %d",
                    board, board);
            hm2->num_leds = board;
        } else {
            hm2->num_leds = want;
        }
        used = (md->instances && hm2->num_leds) ? 1 : 0;
        break;
    }
    case HM2_GTAG_ENCODER:
    case HM2_GTAG_MUXED_ENCODER:
    case HM2_GTAG_STEPGEN:
    case HM2_GTAG_SMARTSERIAL:
    case HM2_GTAG_PWMGEN: {
        int want = requested(hm2, md->gtag);
        if (want > md->instances) {
            hm2_msg(hm2, HM2_ERR, "config.%s=%d, but only %d are available, not loading driver",
                    count_key(md->gtag), want, md->instances);
            return -EINVAL;
        }
        if (want >= 0)
            used = want;
        if (md->gtag == HM2_GTAG_STEPGEN && (md->version == 0 || md->version == 1)) {
            hm2_msg(hm2, HM2_WARN, "WARNING: this firmware has stepgen v%d!", md->version);
            hm2_msg(hm2, HM2_WARN, "WARNING: high step rates require zero stepspace!");
            hm2_msg(hm2, HM2_WARN, "WARNING: upgrade your firmware!");
        }
        if (md->gtag == HM2_GTAG_MUXED_ENCODER && md->version == 2)
            hm2_msg(hm2, HM2_WARN, "WARNING: muxed encoder v2 firmware, upgrade recommended");
        break;
    }
    default: break;
    }
    m->present = true;
    m->md_index = i;
    m->md = *md;
    m->available = md->instances;
    m->used = used;
    hm2_msg(hm2, HM2_INFO, "MD %d: %dx %s v%d: accepted, using %d", i, md->instances, name,
            md->version, used);
    return 0;
}

int hm2_parse_module_descriptors(hostmot2_t *hm2)
{
    /* IOPort first: the other modules' pins hang off it. */
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < hm2->num_mds; i++) {
            bool is_ioport = hm2->md[i].gtag == HM2_GTAG_IOPORT;
            if ((pass == 0) != is_ioport)
                continue;
            if (accept_md(hm2, i)) {
                hm2_msg(hm2, HM2_ERR, "failed to parse Module Descriptor %d", i);
                return -EINVAL;
            }
        }
    }
    return 0;
}
