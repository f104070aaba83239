/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * hm2_test - a fake HostMot2 board for testing the hostmot2 core without
 * hardware (docs/hm2_test.md).  test_pattern=N loads one of LinuxCNC's
 * register images (spec §15.1, writes discarded); image=FILE loads a
 * register image file instead (writes stored, so register effects can be
 * read back with enable_raw), with the geometry of board=NAME.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "hal.h"
#include "hm2/hostmot2.h"
#include "test_patterns.h"
#include "rtapi.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("hm2stack");
MODULE_DESCRIPTION("Test driver for HostMot2 devices");

static int test_pattern = 0;
RTAPI_MP_INT(test_pattern, "The test pattern to show to the HostMot2 driver.");
static char *image = NULL;
RTAPI_MP_STRING(image, "Register image file (65536 bytes, or a 1024-byte IDROM) instead of a pattern");
static char *board = NULL;
RTAPI_MP_STRING(board, "Board whose connectors the image= board has (default 5i20)");
static char *config = NULL;
RTAPI_MP_STRING(config, "hostmot2 config string for the board");

/* The one board of this module (found again by rtapi_app_exit). */
static struct hm2_image_llio *fake;
static int comp_id = -1;

static int setup_image(void)
{
    const struct hm2_board_info *b = hm2_board_lookup(board && *board ? board : "5i20");
    if (!b) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_test: unknown board '%s'\n", board);
        return -EINVAL;
    }
    hm2_image_llio_init(fake, "hm2_test.0");
    hm2_image_llio_set_board(fake, b, 0);
    char err[256];
    int r = hm2_image_llio_load(fake, image, err, sizeof(err));
    if (r)
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_test: %s\n", err);
    return r;
}

int rtapi_app_main(void)
{
    int r;
    fake = calloc(1, sizeof(*fake));
    if (!fake) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_test: out of memory\n");
        return -ENOMEM;
    }
    if (image && *image) {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_test: loading HostMot2 test driver with image %s\n",
                        image);
        r = setup_image();
    } else {
        rtapi_print_msg(RTAPI_MSG_ERR, "hm2_test: loading HostMot2 test driver with test pattern %d\n",
                        test_pattern);
        r = hm2_test_pattern_setup(fake, test_pattern, 0);
        if (r)
            rtapi_print_msg(RTAPI_MSG_ERR, "hm2_test: unknown test pattern %d\n", test_pattern);
    }
    if (r)
        goto fail;
    comp_id = hal_init("hm2_test");
    if (comp_id < 0) {
        r = comp_id;
        goto fail;
    }
    fake->llio.comp_id = comp_id;
    r = hm2_register(&fake->llio, config);
    if (r) {
        rtapi_print_msg(RTAPI_MSG_ERR, "%s: hm2_test fails HM2 registration\n", fake->llio.name);
        hal_exit(comp_id);
        r = -EIO;
        goto fail;
    }
    if (image && *image)
        rtapi_print("%s: initialized hm2 test image %s\n", fake->llio.name, image);
    else
        rtapi_print("%s: initialized hm2 test-pattern %d\n", fake->llio.name, test_pattern);
    hal_ready(comp_id);
    return 0;
fail:
    free(fake);
    fake = NULL;
    return r;
}

void rtapi_app_exit(void)
{
    if (fake) {
        hm2_unregister(&fake->llio);
        free(fake);
        fake = NULL;
    }
    if (comp_id >= 0)
        hal_exit(comp_id);
    rtapi_print("hm2_test: driver unloaded\n");
}
