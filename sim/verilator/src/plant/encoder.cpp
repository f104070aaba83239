// SPDX-License-Identifier: GPL-2.0-or-later
//
// encoder.cpp - quadrature encoder output (encoder.h).
#include "encoder.h"

#include <algorithm>
#include <cmath>

namespace vb::plant {

double Encoder::uniform()
{
    // 53 random bits -> [0, 1): the same on every platform (the standard
    // distributions are not specified bit for bit).
    return static_cast<double>(rng_() >> 11) * 0x1.0p-53;
}

void Encoder::configure(const EncoderParams &p, double counts0, uint64_t t0)
{
    p_ = p;
    rng_.seed(p.seed);
    last_ = counts0;
    count_ = target_ = static_cast<int64_t>(std::floor(counts0));
    moves_.clear();
    in_glitch_ = false;
    glitches_ = 0;
    glitch_at_ = glitch_end_ = UINT64_MAX;
    if (p_.glitch_rate > 0 && p_.glitch_ns > 0)
        next_glitch(t0);
    levels();
}

void Encoder::next_glitch(uint64_t from)
{
    // Exponential intervals: a Poisson process of the mean rate.
    double u = uniform();
    double dt = -std::log(1.0 - u) / p_.glitch_rate * 1e9;
    glitch_at_ = from + static_cast<uint64_t>(dt) + 1;
    glitch_on_b_ = uniform() < 0.5;
}

void Encoder::levels()
{
    static const bool kA[4] = {false, true, true, false}, kB[4] = {false, false, true, true};
    auto q = static_cast<unsigned>(count_ & 3);
    bool a = kA[q], b = kB[q];
    if (p_.reverse)
        std::swap(a, b);
    if (in_glitch_)
        (glitch_on_b_ ? b : a) = !(glitch_on_b_ ? b : a);
    level_a_ = a;
    level_b_ = b;
    level_i_ = false;
    if (p_.counts_per_rev > 0) {
        int64_t m = ((count_ - p_.index_count) % p_.counts_per_rev + p_.counts_per_rev) %
                    p_.counts_per_rev;
        level_i_ = m == 0;
    }
}

void Encoder::plan(double counts, uint64_t t, uint64_t h)
{
    if (p_.jitter > 0)
        counts += (2 * uniform() - 1) * p_.jitter;
    auto target = static_cast<int64_t>(std::floor(counts));
    double span = counts - last_;
    // Transitions between the last planned count and the new one, spread
    // over the next step where the straight line from last_ to counts
    // crosses each count boundary.
    int64_t c = target_;
    while (c != target) {
        int64_t next = c < target ? c + 1 : c - 1;
        double boundary = static_cast<double>(c < target ? next : c);
        double f = span != 0 ? (boundary - last_) / span : 0.0;
        f = std::clamp(f, 0.0, 1.0);
        uint64_t when = t + static_cast<uint64_t>(f * static_cast<double>(h));
        // one state at a time: transitions at least 1 ns apart
        if (!moves_.empty() && when <= moves_.back().t)
            when = moves_.back().t + 1;
        moves_.push_back(Move{when, next});
        c = next;
    }
    target_ = target;
    last_ = counts;
}

uint64_t Encoder::next_event() const
{
    uint64_t t = moves_.empty() ? UINT64_MAX : moves_.front().t;
    return std::min({t, glitch_at_, glitch_end_});
}

void Encoder::run(uint64_t t)
{
    bool changed = false;
    while (!moves_.empty() && moves_.front().t <= t) {
        count_ = moves_.front().count;
        moves_.pop_front();
        changed = true;
    }
    if (glitch_end_ <= t) {
        in_glitch_ = false;
        glitch_end_ = UINT64_MAX;
        next_glitch(t);
        changed = true;
    }
    if (glitch_at_ <= t) {
        in_glitch_ = true;
        glitches_++;
        glitch_end_ = glitch_at_ + p_.glitch_ns;
        glitch_at_ = UINT64_MAX;
        changed = true;
    }
    if (changed)
        levels();
}

} // namespace vb::plant
