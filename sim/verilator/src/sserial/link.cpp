// SPDX-License-Identifier: GPL-2.0-or-later
//
// link.cpp - the wire side of a virtual Smart Serial remote (link.h).
#include "link.h"

#include <cerrno>
#include <cmath>
#include <cstdio>

namespace vb::sserial {

namespace {
constexpr double kTurnaroundBits = 2;  // answer starts this long after the host's CRC
constexpr double kFrameGapBits = 24;   // a longer pause between bytes starts a new frame
} // namespace

uint8_t crc8(const uint8_t *p, size_t n)
{
    uint8_t c = 0;
    for (size_t i = 0; i < n; i++) {
        c ^= p[i];
        for (int k = 0; k < 8; k++)
            c = (c & 0x80) ? static_cast<uint8_t>((c << 1) ^ 0x07) : static_cast<uint8_t>(c << 1);
    }
    return c;
}

void put_bits(std::vector<uint8_t> &v, unsigned pos, unsigned width, uint32_t value)
{
    for (unsigned k = 0; k < width; k++) {
        unsigned b = pos + k;
        if (b / 8 >= v.size())
            return;
        uint8_t m = static_cast<uint8_t>(1u << (b % 8));
        if ((value >> k) & 1u)
            v[b / 8] |= m;
        else
            v[b / 8] &= static_cast<uint8_t>(~m);
    }
}

uint32_t get_bits(const std::vector<uint8_t> &v, unsigned pos, unsigned width)
{
    uint32_t x = 0;
    for (unsigned k = 0; k < width; k++) {
        unsigned b = pos + k;
        if (b / 8 < v.size() && ((v[b / 8] >> (b % 8)) & 1u))
            x |= 1u << k;
    }
    return x;
}

Link::Link(uint32_t tx_pin, uint32_t rx_pin, double bit_ns, std::unique_ptr<Personality> p)
    : tx_pin_(tx_pin), rx_pin_(rx_pin), bit_ns_(bit_ns), p_(std::move(p))
{
}

uint64_t Link::at(uint64_t t0, double bits) const
{
    return t0 + static_cast<uint64_t>(std::llround(bits * bit_ns_));
}

uint64_t Link::next_event() const
{
    uint64_t n = PinBank::kNever;
    if (rx_active_)
        n = rx_next_;
    if (tx_i_ < tx_levels_.size())
        n = std::min(n, at(tx_t0_, static_cast<double>(tx_i_)));
    return n;
}

void Link::on_tx(bool level, uint64_t t)
{
    if (level || rx_active_)
        return;
    // a start bit: sample it in its middle, then every bit after it
    rx_active_ = true;
    rx_t0_ = t;
    rx_k_ = 0;
    rx_byte_ = 0;
    rx_next_ = at(t, 0.5);
}

void Link::run(uint64_t t, PinBank &pins)
{
    while (tx_i_ < tx_levels_.size() && at(tx_t0_, static_cast<double>(tx_i_)) <= t) {
        uint64_t when = at(tx_t0_, static_cast<double>(tx_i_));
        pins.agent_set(rx_pin_, tx_levels_[tx_i_] != 0, when);
        tx_i_++;
    }
    while (rx_active_ && rx_next_ <= t) {
        bool v = pins.level(tx_pin_);
        if (rx_k_ == 0) {
            if (v) {
                rx_active_ = false; // a glitch, not a start bit
                break;
            }
        } else if (rx_k_ <= 8) {
            if (v)
                rx_byte_ |= static_cast<uint8_t>(1u << (rx_k_ - 1));
        } else {
            rx_active_ = false;
            if (v) {
                got_byte(rx_byte_, at(rx_t0_, 10));
            } else {
                bad_++; // framing error: the frame is lost
                drop_frame();
            }
            break;
        }
        rx_k_++;
        rx_next_ = at(rx_t0_, rx_k_ + 0.5);
    }
}

void Link::drop_frame()
{
    frame_.clear();
}

// Length of the host frame (CRC included) that starts with frame_, 0 while
// not known yet, -1 for an unknown command.
int Link::frame_length() const
{
    switch (frame_[0]) {
    case 0x01: return 3;
    case 0x02: return 5;
    case 0x03: return frame_.size() >= 4 ? 5 + frame_[3] : 0;
    case 0x04: return 2 + (out_bits_ + 7) / 8;
    default: return -1;
    }
}

void Link::got_byte(uint8_t b, uint64_t t_end)
{
    if (!frame_.empty() && rx_t0_ > last_end_ && static_cast<double>(rx_t0_ - last_end_) >
                                                     kFrameGapBits * bit_ns_)
        drop_frame(); // the rest of an earlier frame never came
    last_end_ = t_end;
    frame_.push_back(b);
    int n = frame_length();
    if (n < 0) {
        bad_++;
        drop_frame();
        return;
    }
    if (n == 0 || static_cast<int>(frame_.size()) < n)
        return;
    frames_++;
    std::vector<uint8_t> reply;
    bool ok = crc8(frame_.data(), frame_.size() - 1) == frame_.back() && answer(reply);
    drop_frame();
    if (!ok) {
        bad_++;
        return;
    }
    if (!plugged_) {
        unanswered_++;
        return;
    }
    reply.push_back(crc8(reply.data(), reply.size()));
    tx_levels_.clear();
    for (uint8_t x : reply) {
        tx_levels_.push_back(0);
        for (int k = 0; k < 8; k++)
            tx_levels_.push_back((x >> k) & 1u);
        tx_levels_.push_back(1);
    }
    tx_i_ = 0;
    tx_t0_ = at(t_end, kTurnaroundBits);
}

// The reply to the frame in frame_ (CRC checked); false: no answer.
bool Link::answer(std::vector<uint8_t> &reply)
{
    const std::vector<uint8_t> &f = frame_;
    uint32_t addr = f.size() >= 3 ? (f[1] | f[2] << 8) : 0;
    if (!plugged_)
        return true; // heard, but the cable is cut: nothing comes back (unanswered)
    switch (f[0]) {
    case 0x01: {
        uint8_t in = 0, out = 0;
        if (!p_->start(f[1], in, out)) {
            started_ = false;
            return false;
        }
        discovers_++;
        started_ = true;
        mode_ = f[1];
        in_bits_ = in;
        out_bits_ = out;
        std::array<uint8_t, 4> nm = p_->name();
        reply.assign(nm.begin(), nm.end());
        for (int k = 0; k < 4; k++)
            reply.push_back(static_cast<uint8_t>(p_->unit() >> (8 * k)));
        for (uint8_t x : {0, 0, 0, 0})
            reply.push_back(x); // PTOC, GTOC: no table of contents
        reply.push_back(in);
        reply.push_back(out);
        return true;
    }
    case 0x02:
        for (uint32_t i = 0; i < f[3]; i++)
            reply.push_back(memory_.count(addr + i) ? memory_.at(addr + i) : 0);
        return true;
    case 0x03:
        for (uint32_t i = 0; i < f[3]; i++)
            memory_[addr + i] = f[4 + i];
        reply.push_back(0);
        return true;
    default: { // 0x04 process data
        if (!started_)
            return false;
        process_++;
        std::vector<uint8_t> out(f.begin() + 1, f.end() - 1), in((in_bits_ + 7) / 8, 0);
        uint8_t status = 0;
        p_->process(out, in, status);
        reply.push_back(status);
        reply.insert(reply.end(), in.begin(), in.end());
        return true;
    }
    }
}

void Link::set_plugged(bool on, uint64_t now, PinBank &pins)
{
    if (on == plugged_)
        return;
    plugged_ = on;
    if (!on) {
        tx_levels_.clear();
        tx_i_ = 0;
        pins.agent_set(rx_pin_, true, now);
    } else {
        started_ = false; // powered up again: needs a new discovery
    }
}

std::string Link::json() const
{
    char b[256];
    std::snprintf(b, sizeof b,
                  "\"plugged\": %s, \"started\": %s, \"mode\": %u, \"in_bits\": %u, "
                  "\"out_bits\": %u, \"frames\": %llu, \"process\": %llu, \"discovers\": %llu, "
                  "\"bad\": %llu, \"unanswered\": %llu",
                  plugged_ ? "true" : "false", started_ ? "true" : "false", mode_, in_bits_,
                  out_bits_, static_cast<unsigned long long>(frames_),
                  static_cast<unsigned long long>(process_),
                  static_cast<unsigned long long>(discovers_),
                  static_cast<unsigned long long>(bad_),
                  static_cast<unsigned long long>(unanswered_));
    return b;
}

} // namespace vb::sserial
