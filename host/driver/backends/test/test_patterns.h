/* SPDX-License-Identifier: GPL-2.0-or-later */
/*
 * test_patterns.h - the register images of the hm2_test fake board
 * (spec §15.1), shared by the hm2_test module and the unit tests.
 */
#ifndef HM2_TEST_PATTERNS_H
#define HM2_TEST_PATTERNS_H

#include "hm2/llio_image.h"

#define HM2_TEST_NUM_PATTERNS 15

/* Set up im (name hm2_test.<index>, geometry, image) for pattern n.
 * Returns 0, or -EINVAL for an unknown pattern. */
int hm2_test_pattern_setup(struct hm2_image_llio *im, int pattern, int index);

#endif
