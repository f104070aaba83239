// SPDX-License-Identifier: GPL-2.0-or-later
//
// plant_test.h - the small harness of the plant model tests.
#ifndef VBOARD_PLANT_TEST_H
#define VBOARD_PLANT_TEST_H

#include <cmath>
#include <cstdio>
#include <string>

namespace plant_test {

extern int failures;

#define CHECK(cond)                                                                                \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            std::fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);          \
            plant_test::failures++;                                                                \
        }                                                                                          \
    } while (0)

// |got - want| <= rel * |want| (and a tiny absolute floor for want == 0).
#define CHECK_REL(got, want, rel)                                                                  \
    do {                                                                                           \
        double g_ = (got), w_ = (want);                                                            \
        if (!(std::fabs(g_ - w_) <= (rel) * std::fabs(w_) + 1e-300)) {                             \
            std::fprintf(stderr, "%s:%d: %s = %.17g, want %.17g (rel %.3g > %.3g)\n", __FILE__,   \
                         __LINE__, #got, g_, w_, std::fabs(g_ - w_) / std::fabs(w_), (double)(rel)); \
            plant_test::failures++;                                                                \
        }                                                                                          \
    } while (0)

// |got - want| <= rel * max(|want|, scale)
#define CHECK_CLOSE(got, want, rel, scale)                                                         \
    do {                                                                                           \
        double g_ = (got), w_ = (want), s_ = std::fmax(std::fabs(w_), std::fabs(scale));          \
        if (!(std::fabs(g_ - w_) <= (rel) * s_)) {                                                 \
            std::fprintf(stderr, "%s:%d: %s = %.17g, want %.17g (rel %.3g of %.3g > %.3g)\n",      \
                         __FILE__, __LINE__, #got, g_, w_, std::fabs(g_ - w_) / s_, s_,           \
                         (double)(rel));                                                           \
            plant_test::failures++;                                                                \
        }                                                                                          \
    } while (0)

#define CHECK_CONTAINS(text, part)                                                                 \
    do {                                                                                           \
        std::string t_ = (text), p_ = (part);                                                      \
        if (t_.find(p_) == std::string::npos) {                                                    \
            std::fprintf(stderr, "%s:%d: '%s' does not contain '%s'\n", __FILE__, __LINE__,       \
                         t_.c_str(), p_.c_str());                                                  \
            plant_test::failures++;                                                                \
        }                                                                                          \
    } while (0)

void models();  // test_plant_models.cpp
void config();  // test_plant_config.cpp
void machine(); // test_plant_machine.cpp

} // namespace plant_test

#endif // VBOARD_PLANT_TEST_H
