// SPDX-License-Identifier: GPL-2.0-or-later
//
// pins.cpp - the virtual board's pin layer (see pins.h).
#include "pins.h"

#include <algorithm>
#include <cerrno>
#include <cmath>

namespace vb {

namespace {
constexpr int kMaxLoopDepth = 8; // loop chains deeper than this are cut (cycles)

std::string pin_range_error(const char *what, uint32_t pin, uint32_t n)
{
    return std::string(what) + ": I/O pin " + std::to_string(pin) +
           " does not exist (this board has pins 0.." + std::to_string(n - 1) + ")";
}
} // namespace

PinBank::PinBank(uint32_t n)
    : n_(n), fout_((n + 31) / 32, 0), foe_((n + 31) / 32, 0), in_((n + 31) / 32, 0),
      scratch_((n + 31) / 32, 0), ext_(n, kNone), srcval_(n, 0), st_(n), watch_(n, 0),
      owned_(n, 0)
{
    // Undriven pins read 1 (pull-ups).
    for (uint32_t p = 0; p < n_; p++)
        set_bit(in_, p, true);
}

bool PinBank::compute(uint32_t pin) const
{
    if (bit(foe_, pin))
        return bit(fout_, pin);
    switch (ext_[pin]) {
    case kLow: return false;
    case kHigh: return true;
    default: break;
    }
    for (const Loop &l : loops_)
        if (l.to == pin)
            return level(l.from) != l.invert;
    if (ext_[pin] == kQuad || ext_[pin] == kPlant)
        return srcval_[pin];
    return true;
}

void PinBank::set_level(uint32_t pin, bool v, uint64_t now)
{
    Stats &s = st_[pin];
    uint64_t dt = now - s.last_change;
    if (v) {
        if (s.have_fall) {
            s.last_low = dt;
            s.min_low = std::min(s.min_low, dt);
        }
        if (s.have_rise)
            s.period = now - s.last_rise;
        s.last_rise = now;
        s.have_rise = true;
        s.rising++;
    } else {
        if (s.have_rise) {
            s.last_high = dt;
            s.min_high = std::min(s.min_high, dt);
        }
        s.high_total += dt;
        s.have_fall = true;
        s.falling++;
    }
    s.last_change = now;
    set_bit(in_, pin, v);
    if (watch_[pin] && agent_)
        agent_->on_pin(pin, v, now);
}

void PinBank::set_agent(PinAgent *agent)
{
    agent_ = agent;
    update_next_event();
}

void PinBank::own(uint32_t pin, bool level, uint64_t now)
{
    owned_[pin] = 1;
    srcval_[pin] = level;
    if (ext_[pin] == kNone)
        ext_[pin] = kPlant;
    refresh(pin, now);
}

void PinBank::refresh(uint32_t pin, uint64_t now, int depth)
{
    bool v = compute(pin);
    if (v == level(pin))
        return;
    set_level(pin, v, now);
    if (depth >= kMaxLoopDepth)
        return;
    for (size_t i = 0; i < loops_.size(); i++)
        if (loops_[i].from == pin)
            refresh(loops_[i].to, now, depth + 1);
}

void PinBank::apply_fpga(const uint32_t *out, const uint32_t *oe, uint64_t now)
{
    std::vector<uint32_t> &changed = scratch_; // no allocation per edge
    for (uint32_t w = 0; w < in_.size(); w++) {
        changed[w] = (out[w] ^ fout_[w]) | (oe[w] ^ foe_[w]);
        fout_[w] = out[w];
        foe_[w] = oe[w];
    }
    for (uint32_t w = 0; w < in_.size(); w++)
        for (uint32_t m = changed[w]; m; m &= m - 1) {
            uint32_t pin = w * 32 + static_cast<uint32_t>(__builtin_ctz(m));
            if (pin < n_)
                refresh(pin, now);
        }
}

void PinBank::release_fpga(uint64_t now)
{
    std::vector<uint32_t> zero(in_.size(), 0);
    set_fpga(zero.data(), zero.data(), now);
}

int PinBank::drive(uint32_t pin, uint32_t mode, uint64_t now, std::string &err)
{
    if (pin >= n_) {
        err = pin_range_error("drive", pin, n_);
        return -EINVAL;
    }
    if (mode > VB_DRIVE_HIGH) {
        err = "drive: I/O pin " + std::to_string(pin) + ": mode " + std::to_string(mode) +
              " is not release (0), low (1) or high (2)";
        return -EINVAL;
    }
    if (mode == VB_DRIVE_RELEASE) {
        bool quad = false;
        for (const Quad &q : quads_)
            quad = quad || q.a == pin || q.b == pin || q.index == pin;
        ext_[pin] = quad ? kQuad : owned_[pin] ? kPlant : kNone;
    } else {
        ext_[pin] = mode == VB_DRIVE_LOW ? kLow : kHigh;
    }
    refresh(pin, now);
    return 0;
}

int PinBank::loop(uint32_t from, uint32_t to, bool invert, uint64_t now, std::string &err)
{
    if (from >= n_) {
        err = pin_range_error("loop source", from, n_);
        return -EINVAL;
    }
    if (to == UINT32_MAX) {
        std::vector<uint32_t> dests;
        for (const Loop &l : loops_)
            if (l.from == from)
                dests.push_back(l.to);
        loops_.erase(std::remove_if(loops_.begin(), loops_.end(),
                                    [from](const Loop &l) { return l.from == from; }),
                     loops_.end());
        for (uint32_t d : dests)
            refresh(d, now);
        return 0;
    }
    if (to >= n_) {
        err = pin_range_error("loop destination", to, n_);
        return -EINVAL;
    }
    if (to == from) {
        err = "loop: I/O pin " + std::to_string(from) + " cannot be looped into itself";
        return -EINVAL;
    }
    // A pin has one loop source: a new loop into `to` replaces the old one.
    loops_.erase(std::remove_if(loops_.begin(), loops_.end(),
                                [to](const Loop &l) { return l.to == to; }),
                 loops_.end());
    loops_.push_back(Loop{from, to, invert});
    refresh(to, now);
    return 0;
}

void PinBank::quad_levels(const Quad &q, uint64_t now)
{
    static const uint8_t kA[4] = {0, 1, 1, 0}, kB[4] = {0, 0, 1, 1};
    unsigned state = static_cast<unsigned>(q.position & 3);
    srcval_[q.a] = kA[state];
    srcval_[q.b] = kB[state];
    if (q.index != UINT32_MAX) {
        int64_t every = q.index_every;
        bool idx = every > 0 && ((q.position % every) + every) % every == 0;
        srcval_[q.index] = idx;
        refresh(q.index, now);
    }
    refresh(q.a, now);
    refresh(q.b, now);
}

void PinBank::quad_schedule(Quad &q)
{
    if (!q.running) {
        q.next = kNever;
        return;
    }
    // Count k happens at t0 + (k - k0) / |rate| exactly (no accumulated
    // rounding: every count time is computed from the rebase point).
    double per = 1e9 / std::fabs(q.rate);
    q.next = q.t0 + static_cast<uint64_t>(std::llround(static_cast<double>(q.k0 + 1) * per));
}

void PinBank::update_next_event()
{
    next_event_ = agent_ ? agent_->next_event() : kNever;
    for (const Quad &q : quads_)
        next_event_ = std::min(next_event_, q.next);
}

void PinBank::run_events(uint64_t now)
{
    while (next_event_ <= now) {
        uint64_t t = next_event_;
        for (Quad &q : quads_) {
            if (q.next != t)
                continue;
            q.position += q.rate > 0 ? 1 : -1;
            q.k0++;
            quad_levels(q, t);
            quad_schedule(q);
        }
        if (agent_ && agent_->next_event() <= t)
            agent_->run(t);
        update_next_event();
    }
}

int PinBank::quad(const vb_quad &in, uint64_t now, std::string &err)
{
    if (in.pin_a >= n_ || in.pin_b >= n_ || (in.pin_index != UINT32_MAX && in.pin_index >= n_)) {
        uint32_t bad = in.pin_a >= n_ ? in.pin_a : in.pin_b >= n_ ? in.pin_b : in.pin_index;
        err = pin_range_error("quadrature source", bad, n_);
        return -EINVAL;
    }
    if (in.pin_a == in.pin_b || in.pin_a == in.pin_index || in.pin_b == in.pin_index) {
        err = "quadrature source: pins A " + std::to_string(in.pin_a) + ", B " +
              std::to_string(in.pin_b) + " and index must be different";
        return -EINVAL;
    }
    if (!std::isfinite(in.counts_per_s) || std::fabs(in.counts_per_s) > 1e9) {
        err = "quadrature source on pin " + std::to_string(in.pin_a) +
              ": rate must be finite and at most 1e9 counts/s";
        return -EINVAL;
    }
    for (uint32_t p : {in.pin_a, in.pin_b, in.pin_index})
        if (p != UINT32_MAX && owned_[p]) {
            err = "quadrature source: I/O pin " + std::to_string(p) +
                  " is driven by the machine model (vboard --machine)";
            return -EINVAL;
        }
    Quad *q = nullptr;
    for (Quad &e : quads_)
        if (e.a == in.pin_a)
            q = &e;
    if (!q) {
        quads_.push_back(Quad{in.pin_a, in.pin_b, in.pin_index, 0, 0.0, 0, now, 0, kNever, false});
        q = &quads_.back();
    } else {
        // Pins the new source no longer uses stop being source pins.
        for (uint32_t old : {q->b, q->index})
            if (old != UINT32_MAX && old != in.pin_b && old != in.pin_index && ext_[old] == kQuad) {
                ext_[old] = owned_[old] ? kPlant : kNone;
                refresh(old, now);
            }
    }
    q->b = in.pin_b;
    q->index = in.pin_index;
    q->index_every = in.index_every;
    q->rate = in.counts_per_s;
    q->running = in.counts_per_s != 0.0;
    q->t0 = now;
    q->k0 = 0;
    for (uint32_t p : {q->a, q->b, q->index})
        if (p != UINT32_MAX && ext_[p] == kNone)
            ext_[p] = kQuad;
    quad_levels(*q, now);
    quad_schedule(*q);
    update_next_event();
    return 0;
}

int PinBank::probe(uint32_t first, uint32_t count, uint64_t now, std::vector<vb_pin> &out,
                   std::string &err) const
{
    if (first >= n_ || count > n_ - first) {
        err = "probe: pins " + std::to_string(first) + ".." +
              std::to_string(static_cast<uint64_t>(first) + count - 1) +
              " are outside this board's pins 0.." + std::to_string(n_ - 1);
        return -EINVAL;
    }
    for (uint32_t p = first; p < first + count; p++) {
        const Stats &s = st_[p];
        vb_pin v{};
        v.level = level(p);
        v.oe = bit(foe_, p);
        bool looped = false;
        for (const Loop &l : loops_)
            looped = looped || l.to == p;
        uint8_t ext = ext_[p];
        if (ext != kLow && ext != kHigh && looped)
            ext = kLooped;
        v.ext = ext;
        v.rising = s.rising;
        v.falling = s.falling;
        v.last_high_ns = s.last_high;
        v.last_low_ns = s.last_low;
        v.period_ns = s.period;
        v.high_total_ns = s.high_total + (v.level ? now - s.last_change : 0);
        v.total_ns = now - s.since;
        v.min_high_ns = s.min_high;
        v.min_low_ns = s.min_low;
        out.push_back(v);
    }
    return 0;
}

int PinBank::probe_reset(uint32_t first, uint32_t count, uint64_t now, std::string &err)
{
    if (first >= n_ || count > n_ - first) {
        err = "probe reset: pins " + std::to_string(first) + ".." +
              std::to_string(static_cast<uint64_t>(first) + count - 1) +
              " are outside this board's pins 0.." + std::to_string(n_ - 1);
        return -EINVAL;
    }
    for (uint32_t p = first; p < first + count; p++) {
        Stats s;
        s.since = now;
        s.last_change = now;
        st_[p] = s;
    }
    return 0;
}

} // namespace vb
