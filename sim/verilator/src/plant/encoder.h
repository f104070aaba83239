// SPDX-License-Identifier: GPL-2.0-or-later
//
// encoder.h - a quadrature encoder (A, B, index) on a shaft or a scale.
//
// The model hands the encoder the shaft position (in counts) at the end of
// every step; the encoder then puts the count transitions of that step on
// its pins during the next step, each at the time linear interpolation
// places it (so the pins lag the shaft by one step, a few microseconds: a
// fast encoder's latency).  A count change moves one quadrature state: A
// leads B counting up.  The index is high during one count per revolution.
// Optional imperfections, from a seeded generator (runs repeat exactly):
// glitches (one line inverted for a short time, at random times with a
// mean rate) and jitter (the position read with a uniform error).
#ifndef VBOARD_PLANT_ENCODER_H
#define VBOARD_PLANT_ENCODER_H

#include <cstdint>
#include <deque>
#include <random>

namespace vb::plant {

struct EncoderParams {
    int64_t counts_per_rev = 0; // index period in counts (0: no index)
    int64_t index_count = 0;    // the count (mod counts_per_rev) during which the index is high
    bool reverse = false;       // B leads A counting up
    double glitch_rate = 0;     // glitches per second (0: none)
    uint64_t glitch_ns = 0;     // their width
    double jitter = 0;          // counts, uniform +-jitter on every reading
    uint64_t seed = 1;
};

class Encoder {
  public:
    // t0: board time now, counts0: the position now.
    void configure(const EncoderParams &p, double counts0, uint64_t t0);
    // The position at time t (end of a step of h ns): schedules the
    // transitions for [t, t + h).
    void plan(double counts, uint64_t t, uint64_t h);
    // Next pin change (UINT64_MAX: none) and running it.
    uint64_t next_event() const;
    // Apply every change due at or before t.
    void run(uint64_t t);

    bool a() const { return level_a_; }
    bool b() const { return level_b_; }
    bool index() const { return level_i_; }
    int64_t count() const { return count_; }
    uint64_t glitches() const { return glitches_; }

  private:
    struct Move {
        uint64_t t;
        int64_t count;
    };
    void levels();
    void next_glitch(uint64_t from);
    double uniform();

    EncoderParams p_;
    int64_t count_ = 0;  // the count on the pins
    int64_t target_ = 0; // the count planned last
    double last_ = 0;    // the position planned last
    std::deque<Move> moves_;
    bool level_a_ = false, level_b_ = false, level_i_ = false;
    // glitches
    std::mt19937_64 rng_;
    uint64_t glitch_at_ = UINT64_MAX, glitch_end_ = UINT64_MAX;
    bool glitch_on_b_ = false, in_glitch_ = false;
    uint64_t glitches_ = 0;
};

} // namespace vb::plant

#endif // VBOARD_PLANT_ENCODER_H
