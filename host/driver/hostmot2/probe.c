/* SPDX-License-Identifier: GPL-2.0-or-later */
/* hm2_probe: everything in the load sequence (spec §11 steps 1-7) that
 * does not touch HAL, so the pinout tool and the tests can use it alone. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/hm2.h"

#define HM2_MAX_FIRMWARE_SIZE (64u * 1024u * 1024u)

int hm2_load_firmware(hostmot2_t *hm2, const char *search_path)
{
    hm2_llio_t *llio = hm2->llio;
    const char *name = hm2->config.firmware;
    char pathbuf[1024], path[1024], err[128];
    uint8_t *buf = NULL;
    size_t len = 0;
    struct hm2_bitfile bf;
    int r;

    if (!llio->program_fpga)
        return 0; /* flash-configured board: firmware= is ignored */
    if (name[0] == '\0') {
        hm2_msg_core(hm2->log, hm2->log_ctx, HM2_PRINT,
                     "no firmware specified in config modparam!  the board had better have "
                     "firmware configured already, or this won't work");
        return 0;
    }
    if (!search_path)
        search_path = hm2_firmware_default_path(pathbuf, sizeof(pathbuf));
    r = hm2_firmware_find(search_path, name, path, sizeof(path));
    if (r) {
        hm2_msg(hm2, HM2_ERR, "firmware %s not found", name);
        hm2_msg(hm2, HM2_ERR, "install the package containing the firmware.");
        if (r == -EINVAL)
            hm2_msg(hm2, HM2_ERR, "    (firmware names are relative to the search path and may "
                                  "not contain '..')");
        else
            hm2_msg(hm2, HM2_ERR, "    (searched %s)", search_path);
        return -ENOENT;
    }
    r = hm2_read_file(path, HM2_MAX_FIRMWARE_SIZE, &buf, &len);
    if (r) {
        hm2_msg(hm2, HM2_ERR, "request for firmware %s failed, aborting hm2_register (r=%d)", name,
                r);
        return r;
    }
    r = hm2_bitfile_parse(buf, len, &bf, err, sizeof(err));
    if (r) {
        hm2_msg_core(hm2->log, hm2->log_ctx, HM2_ERR, "%s", err);
        hm2_msg(hm2, HM2_ERR, "firmware %s fails verification, aborting hm2_register", name);
        goto out;
    }
    hm2_msg(hm2, HM2_INFO, "firmware %s:", name);
    hm2_msg(hm2, HM2_INFO, "    %s %s %s", bf.design ? bf.design : "(no design name)",
            bf.date ? bf.date : "(no date)", bf.time ? bf.time : "(no time)");
    hm2_msg(hm2, HM2_INFO, "    Part Name: %s", bf.part);
    hm2_msg(hm2, HM2_INFO, "    FPGA Config: %u bytes", bf.size);
    if (llio->fpga_part_number && llio->fpga_part_number[0] &&
        strcmp(llio->fpga_part_number, bf.part) != 0) {
        hm2_msg(hm2, HM2_ERR, "board has FPGA '%s', but the firmware in %s is for FPGA '%s'",
                llio->fpga_part_number, name, bf.part);
        r = -EINVAL;
        goto out;
    }
    r = llio->reset(llio);
    if (r) {
        hm2_msg(hm2, HM2_ERR, "failed to reset fpga, aborting hm2_register");
        goto out;
    }
    r = llio->program_fpga(llio, &bf);
    if (r) {
        hm2_msg(hm2, HM2_ERR, "failed to program fpga, aborting hm2_register");
        goto out;
    }
out:
    free(buf);
    return r;
}

void hm2_free(hostmot2_t *hm2)
{
    if (!hm2)
        return;
    free(hm2->pin);
    free(hm2);
}

hostmot2_t *hm2_probe(hm2_llio_t *llio, const char *config, const struct hm2_options *opts,
                      hm2_log_fn log, void *log_ctx, int *err)
{
    char msg[160];
    int r;

    r = hm2_llio_validate(llio, msg, sizeof(msg));
    if (r) {
        hm2_msg_core(log, log_ctx, HM2_ERR, "invalid llio: %s", msg);
        *err = r;
        return NULL;
    }
    hostmot2_t *hm2 = calloc(1, sizeof(*hm2));
    if (!hm2) {
        hm2_msg_core(log, log_ctx, HM2_ERR, "out of memory allocating board %s", llio->name);
        *err = -ENOMEM;
        return NULL;
    }
    hm2->llio = llio;
    hm2->log = log;
    hm2->log_ctx = log_ctx;
    if (opts)
        hm2->debug = opts->debug;

    r = hm2_config_parse(config, &hm2->config, msg, sizeof(msg));
    if (r) {
        hm2_msg(hm2, HM2_ERR, "%s", msg);
        hm2_msg(hm2, HM2_ERR, "failed to parse config string \"%s\"", config ? config : "");
        goto fail;
    }
    if ((r = hm2_load_firmware(hm2, opts ? opts->firmware_path : NULL)))
        goto fail;
    hm2_msg(hm2, HM2_PRINT, "Low Level init %s", HM2_VERSION);
    if ((r = hm2_read_idrom(hm2)))
        goto fail;
    if ((r = hm2_read_pin_descriptors(hm2)))
        goto fail;
    if ((r = hm2_read_module_descriptors(hm2)))
        goto fail;
    if ((r = hm2_parse_module_descriptors(hm2)))
        goto fail;
    if ((r = hm2_allocate_pins(hm2)))
        goto fail;
    *err = 0;
    return hm2;
fail:
    hm2_free(hm2);
    *err = r ? r : -EINVAL;
    return NULL;
}
