// SPDX-License-Identifier: GPL-2.0-or-later
//
// pins.h - the pin layer shared by every virtual board.
//
// Every I/O pin has what the FPGA does to it (out, oe) and what the outside
// world does to it (nothing, driven low/high, looped from another pin, a
// quadrature source).  Its level is, in this order of precedence: the
// FPGA's output when oe = 1; the external drive; the loop source's level
// (optionally inverted); the quadrature source; else 1 (pull-up).
//
// Probe statistics (edge counts, last pulse widths, period, duty) follow the
// level and are kept in board ns.  They are updated on every level change,
// so they are exact at the resolution at which the board reports changes
// (every edge of its fastest clock).
//
// Boards call set_fpga() after clock edges with the firmware's out/oe
// vectors and feed inputs() back into the firmware; before each clock edge
// they call run_events() when now >= next_event_ns() (quadrature sources).
// Pin vectors are 32-bit words, pin 0 in bit 0 of word 0.
#ifndef VBOARD_PINS_H
#define VBOARD_PINS_H

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "vboard/proto.h"

namespace vb {

// Something outside the FPGA that moves with board time and watches or
// drives pins: the plant models of a machine (plant/machine.h).  The pin
// bank calls it in board-time order, before the clock edge that could see
// its effect, like the quadrature sources.
class PinAgent {
  public:
    virtual ~PinAgent() = default;
    // Board time of the agent's next own event (PinBank::kNever: none).
    virtual uint64_t next_event() const = 0;
    // Run every own event due at or before t.
    virtual void run(uint64_t t) = 0;
    // A watched pin changed its level at board time t.
    virtual void on_pin(uint32_t pin, bool level, uint64_t t) = 0;
};

class PinBank {
  public:
    static constexpr uint64_t kNever = std::numeric_limits<uint64_t>::max();

    explicit PinBank(uint32_t n);

    uint32_t size() const { return n_; }
    uint32_t words() const { return static_cast<uint32_t>(in_.size()); }

    // ---- board side ---------------------------------------------------------
    // New FPGA out/oe vectors (words() words each) at board time now.
    // Cheap when nothing changed.
    void set_fpga(const uint32_t *out, const uint32_t *oe, uint64_t now)
    {
        bool same = true;
        for (uint32_t w = 0; w < in_.size(); w++)
            if (out[w] != fout_[w] || oe[w] != foe_[w]) {
                same = false;
                break;
            }
        if (!same)
            apply_fpga(out, oe, now);
    }
    // The level of every pin (what the firmware's inputs see).
    const uint32_t *inputs() const { return in_.data(); }
    // Board time of the next quadrature-source edge (kNever: none).
    uint64_t next_event_ns() const { return next_event_; }
    // Apply every source edge due at or before now.
    void run_events(uint64_t now);
    // The FPGA stops driving everything (blank board, reset).
    void release_fpga(uint64_t now);

    // ---- API (requests) ------------------------------------------------------
    int drive(uint32_t pin, uint32_t mode, uint64_t now, std::string &err);
    int loop(uint32_t from, uint32_t to, bool invert, uint64_t now, std::string &err);
    int quad(const vb_quad &q, uint64_t now, std::string &err);
    int probe(uint32_t first, uint32_t count, uint64_t now, std::vector<vb_pin> &out,
              std::string &err) const;
    int probe_reset(uint32_t first, uint32_t count, uint64_t now, std::string &err);

    // ---- plant models (vboard --machine) -------------------------------------
    // Attach the agent (one; nullptr detaches).  It is told about changes of
    // the pins it watches and sets the level of the pins it owns; an owned
    // pin reads that level unless the FPGA drives it or a DRIVE / loop
    // overrides it (the same precedence as a quadrature source).
    void set_agent(PinAgent *agent);
    PinAgent *agent() const { return agent_; }
    void watch(uint32_t pin) { watch_[pin] = 1; }
    void own(uint32_t pin, bool level, uint64_t now);
    void agent_set(uint32_t pin, bool level, uint64_t now)
    {
        if (srcval_[pin] != level) {
            srcval_[pin] = level;
            refresh(pin, now);
        }
    }
    // The agent's next event changed outside run_events (after attaching).
    void agent_rescheduled() { update_next_event(); }

    bool level(uint32_t pin) const { return (in_[pin >> 5] >> (pin & 31)) & 1u; }

  private:
    struct Stats {
        uint32_t rising = 0, falling = 0;
        uint64_t since = 0;        // reset time
        uint64_t last_change = 0;  // time of the last level change (or reset)
        uint64_t last_rise = 0;
        bool have_rise = false, have_fall = false;
        uint64_t last_high = 0, last_low = 0, period = 0;
        uint64_t high_total = 0;   // closed high intervals since reset
        uint64_t min_high = kNever, min_low = kNever;
    };
    struct Loop {
        uint32_t from, to;
        bool invert;
    };
    struct Quad {
        uint32_t a, b, index, index_every;
        double rate;       // counts per s, signed
        int64_t position;  // counts
        uint64_t t0;       // board time of count k0
        int64_t k0;        // counts done at t0 (rate changes rebase here)
        uint64_t next;     // next count time
        bool running;
    };
    enum Ext : uint8_t { kNone = 0, kLow = 1, kHigh = 2, kLooped = 3, kQuad = 4, kPlant = 5 };

    void apply_fpga(const uint32_t *out, const uint32_t *oe, uint64_t now);
    bool compute(uint32_t pin) const;
    void refresh(uint32_t pin, uint64_t now, int depth = 0);
    void set_level(uint32_t pin, bool v, uint64_t now);
    void quad_levels(const Quad &q, uint64_t now);
    void quad_schedule(Quad &q);
    void update_next_event();
    bool bit(const std::vector<uint32_t> &v, uint32_t pin) const
    {
        return (v[pin >> 5] >> (pin & 31)) & 1u;
    }
    static void set_bit(std::vector<uint32_t> &v, uint32_t pin, bool b)
    {
        if (b)
            v[pin >> 5] |= 1u << (pin & 31);
        else
            v[pin >> 5] &= ~(1u << (pin & 31));
    }

    uint32_t n_;
    std::vector<uint32_t> fout_, foe_, in_, scratch_;
    std::vector<uint8_t> ext_;       // enum Ext
    std::vector<uint8_t> srcval_;    // level from quad source (pins with ext kQuad)
    std::vector<Stats> st_;
    std::vector<Loop> loops_;
    std::vector<Quad> quads_;
    uint64_t next_event_ = kNever;
    PinAgent *agent_ = nullptr;
    std::vector<uint8_t> watch_;  // 1: changes go to the agent
    std::vector<uint8_t> owned_;  // 1: the agent sets this pin's level
};

} // namespace vb

#endif // VBOARD_PINS_H
