// SPDX-License-Identifier: GPL-2.0-or-later
//
// remotes.h - the Smart Serial remote boards on a virtual board's channels
// (vboard --sserial P.C=TYPE; docs/sserial.md, docs/vboard.md).
//
// Remotes is the board's PinAgent: it hears the channels' TxData pins, owns
// their RxData pins, and passes everything else on to the agent that was
// attached before it (the machine of vboard --machine), so both can run.
// Tests reach the remotes with VB_SSERIAL text commands:
//   status                          JSON of every remote
//   set P.C plugged 0|1             the cable
//   set P.C inputs MASK | input N 0|1 | analog N VOLTS | field VOLTS
#ifndef VBOARD_SSERIAL_REMOTES_H
#define VBOARD_SSERIAL_REMOTES_H

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "link.h"
#include "pins.h"

namespace vb::sserial {

struct RemoteSpec {
    unsigned port = 0, chan = 0;
    std::string type;
};

// Parse "P.C=TYPE" (P 0..3, C 0..7).
bool parse_remote(const std::string &arg, RemoteSpec &spec, std::string &err);

class Remotes final : public PinAgent {
  public:
    // pin_names: the board's pins under `firmware` (label, function);
    // clock_low_hz: the firmware's ClockLow.  Fails (false, err) when a
    // channel has no TxData/RxData pin in that firmware or is named twice.
    bool configure(const std::vector<RemoteSpec> &specs, const std::string &firmware,
                   const std::vector<std::pair<std::string, std::string>> &pin_names,
                   uint32_t clock_low_hz, std::string &err);
    // Become the pins' agent at board time now (the agent before stays
    // behind this one).
    void attach(PinBank &pins, uint64_t now);

    uint64_t next_event() const override;
    void run(uint64_t t) override;
    void on_pin(uint32_t pin, bool level, uint64_t t) override;

    int command(const std::string &cmd, uint64_t now, std::string &reply, std::string &err);
    size_t size() const { return links_.size(); }

  private:
    struct Entry {
        RemoteSpec spec;
        std::unique_ptr<Link> link;
    };
    std::string entry_json(const Entry &e) const;
    Entry *find(const std::string &pc);

    std::vector<Entry> links_;
    PinBank *pins_ = nullptr;
    PinAgent *inner_ = nullptr;
    std::vector<int> by_tx_; // TxData pin -> index in links_, -1 none
};

} // namespace vb::sserial

#endif // VBOARD_SSERIAL_REMOTES_H
