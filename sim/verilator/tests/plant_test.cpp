// SPDX-License-Identifier: GPL-2.0-or-later
//
// plant_test.cpp - runs the plant model tests (ctest vboard_plant_tests).
#include "plant_test.h"

namespace plant_test {
int failures = 0;
}

int main()
{
    plant_test::models();
    plant_test::config();
    plant_test::machine();
    if (plant_test::failures) {
        std::fprintf(stderr, "vboard_plant_tests: %d check(s) failed\n", plant_test::failures);
        return 1;
    }
    std::printf("vboard_plant_tests: all checks passed\n");
    return 0;
}
