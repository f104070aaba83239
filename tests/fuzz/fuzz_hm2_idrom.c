/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * libFuzzer target: the hostmot2 probe (ID block, IDROM header, module and
 * pin descriptors, module acceptance, pin allocation and the pin report)
 * over a 5i20 register image whose bytes from 0x0100 on are the input.
 * Every image either probes or is refused with a message; nothing reads or
 * writes outside the image, nothing leaks.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hm2/boards.h"
#include "hm2/hm2.h"
#include "hm2/llio_image.h"

#define FIRST 0x0100u

static struct hm2_image_llio im;

static void sink(void *ctx, int level, const char *line)
{
    int *errors = ctx;
    if (!line)
        abort();
    if (level == HM2_ERR)
        (*errors)++;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > HM2_IMAGE_SIZE - FIRST)
        size = HM2_IMAGE_SIZE - FIRST;
    hm2_image_llio_init(&im, "hm2_5i20.0");
    hm2_image_llio_set_board(&im, hm2_board_lookup("5i20"), 0);
    memcpy(im.mem + FIRST, data, size);
    struct hm2_options opts;
    memset(&opts, 0, sizeof opts);
    opts.firmware_path = "/nonexistent";
    int errors = 0, err = 0;
    hostmot2_t *hm2 = hm2_probe(&im.llio, NULL, &opts, sink, &errors, &err);
    if (hm2) {
        hm2_print_pin_usage(hm2);
        hm2_free(hm2);
    } else if (err >= 0 || errors == 0) {
        abort(); /* a refused image has an error code and a message */
    }
    return 0;
}
