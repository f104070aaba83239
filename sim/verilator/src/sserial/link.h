// SPDX-License-Identifier: GPL-2.0-or-later
//
// link.h - one Smart Serial remote board on one channel of a virtual board.
//
// The remote listens on the channel's TxData pin (the FPGA transmits) and
// answers on its RxData pin, in the frame protocol hdl/hostmot2/
// hm2_sserial_chan.v speaks (this project's own, not Mesa's SSLBP; see
// docs/sserial.md): 8N1 bytes at the channel's bit time, every frame ending
// with a CRC-8 (polynomial 0x07, initial value 0).
//
//   discover  host: 01 mode               remote: name[4] unit[4] ptoc[2]
//                                                 gtoc[2] in_bits out_bits
//   read      host: 02 addr_lo addr_hi n  remote: data[n]
//   write     host: 03 addr_lo addr_hi n data[n]   remote: status
//   process   host: 04 out[ceil(out_bits/8)]       remote: status in[...]
//
// A Link decodes the TxData line from its edges (sampling each bit in its
// middle on board time), answers two bit times after the host's frame, and
// puts its answer on RxData bit by bit at exact board times.  What the
// remote does with process data is its Personality (the board type).
#ifndef VBOARD_SSERIAL_LINK_H
#define VBOARD_SSERIAL_LINK_H

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "pins.h"

namespace vb::sserial {

uint8_t crc8(const uint8_t *p, size_t n);

// Bit fields in a little-endian byte vector (process data).
void put_bits(std::vector<uint8_t> &v, unsigned pos, unsigned width, uint32_t value);
uint32_t get_bits(const std::vector<uint8_t> &v, unsigned pos, unsigned width);

// The board type behind a link.
class Personality {
  public:
    virtual ~Personality() = default;
    virtual std::string type() const = 0;               // "7i76"
    virtual std::array<uint8_t, 4> name() const = 0;    // "7I76"
    virtual uint32_t unit() const = 0;                  // its serial number
    // Start in `mode`: the process data sizes; false: the board has no
    // such mode (it does not answer the discovery).
    virtual bool start(uint8_t mode, uint8_t &in_bits, uint8_t &out_bits) = 0;
    // One process-data exchange: out from the host, in (sized for in_bits)
    // and the status byte back.
    virtual void process(const std::vector<uint8_t> &out, std::vector<uint8_t> &in,
                         uint8_t &status) = 0;
    // "set" keys of the board's own ("input", "analog", ...): 0 or -EINVAL.
    virtual int set(const std::vector<std::string> &args, std::string &err) = 0;
    // Its state as the members of a JSON object (no braces).
    virtual std::string json() const = 0;
};

// Make a personality by type name ("7i76"); nullptr if unknown.
std::unique_ptr<Personality> make_personality(const std::string &type, uint32_t unit);
// The known type names, for messages.
std::string personality_types();

class Link {
  public:
    Link(uint32_t tx_pin, uint32_t rx_pin, double bit_ns, std::unique_ptr<Personality> p);

    uint32_t tx_pin() const { return tx_pin_; }
    uint32_t rx_pin() const { return rx_pin_; }
    Personality &board() { return *p_; }

    uint64_t next_event() const;
    // Run every sample and transmit step due at or before t.
    void run(uint64_t t, PinBank &pins);
    // The TxData line changed at t.
    void on_tx(bool level, uint64_t t);

    // Cable: unplugged stops every answer (a transmission in progress is
    // cut, the line idles high); plugging in again powers the board up:
    // it answers process data only after a new discovery.
    void set_plugged(bool on, uint64_t now, PinBank &pins);
    bool plugged() const { return plugged_; }

    std::string json() const;

  private:
    void got_byte(uint8_t b, uint64_t t_end);
    void drop_frame();
    int frame_length() const;
    bool answer(std::vector<uint8_t> &reply);
    uint64_t at(uint64_t t0, double bits) const;

    uint32_t tx_pin_, rx_pin_;
    double bit_ns_;
    std::unique_ptr<Personality> p_;
    bool plugged_ = true;
    bool started_ = false;
    uint8_t mode_ = 0, in_bits_ = 0, out_bits_ = 0;
    std::map<uint32_t, uint8_t> memory_;
    // receive
    bool rx_active_ = false;
    uint64_t rx_t0_ = 0, rx_next_ = 0, last_end_ = 0;
    int rx_k_ = 0;
    uint8_t rx_byte_ = 0;
    std::vector<uint8_t> frame_;
    // transmit
    std::vector<uint8_t> tx_levels_;
    size_t tx_i_ = 0;
    uint64_t tx_t0_ = 0;
    // counters
    uint64_t frames_ = 0, process_ = 0, discovers_ = 0, bad_ = 0, unanswered_ = 0;
};

} // namespace vb::sserial

#endif // VBOARD_SSERIAL_LINK_H
