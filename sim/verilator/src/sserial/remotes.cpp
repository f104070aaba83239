// SPDX-License-Identifier: GPL-2.0-or-later
//
// remotes.cpp - the set of virtual Smart Serial remotes (remotes.h).
#include "remotes.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <sstream>

namespace vb::sserial {

namespace {

// ClockLow periods per Smart Serial bit: the firmware's divisor, computed
// as tools/hm2gen does (Firmware.sserial_bit_div: 2.5 MBaud nominal).
uint32_t bit_div(uint32_t clock_low_hz)
{
    long d = std::lround(static_cast<double>(clock_low_hz) / 2.5e6);
    return static_cast<uint32_t>(std::max(4L, d));
}

int find_pin(const std::vector<std::pair<std::string, std::string>> &names,
             const std::string &function)
{
    for (size_t i = 0; i < names.size(); i++)
        if (names[i].second == function)
            return static_cast<int>(i);
    return -1;
}

std::vector<std::string> words(const std::string &s)
{
    std::istringstream in(s);
    std::vector<std::string> w;
    std::string x;
    while (in >> x)
        w.push_back(x);
    return w;
}

} // namespace

bool parse_remote(const std::string &arg, RemoteSpec &spec, std::string &err)
{
    size_t eq = arg.find('=');
    if (arg.size() < 5 || arg[1] != '.' || eq != 3 || arg[0] < '0' || arg[0] > '3' ||
        arg[2] < '0' || arg[2] > '7') {
        err = "bad --sserial '" + arg + "': want P.C=TYPE (port P 0..3, channel C 0..7, " +
              "TYPE one of: " + personality_types() + ")";
        return false;
    }
    spec.port = static_cast<unsigned>(arg[0] - '0');
    spec.chan = static_cast<unsigned>(arg[2] - '0');
    spec.type = arg.substr(4);
    if (spec.type == "7i77" && spec.chan == 7) {
        err = "bad --sserial '" + arg + "': a 7i77 takes two channels (C and C+1), C must be 0..6";
        return false;
    }
    if (spec.type == "7i77-analog" || !make_personality(spec.type, 0)) {
        err = "bad --sserial '" + arg + "': unknown remote board '" + spec.type +
              "' (known: " + personality_types() + ")";
        return false;
    }
    return true;
}

bool Remotes::configure(const std::vector<RemoteSpec> &specs, const std::string &firmware,
                        const std::vector<std::pair<std::string, std::string>> &names,
                        uint32_t clock_low_hz, std::string &err)
{
    double bit_ns = bit_div(clock_low_hz) * 1e9 / clock_low_hz;
    by_tx_.assign(names.size(), -1);
    // a 7I77 is two channels: field I/O on C, its analog servo part on C+1
    std::vector<RemoteSpec> all;
    for (const RemoteSpec &s : specs) {
        all.push_back(s);
        if (s.type == "7i77")
            all.push_back(RemoteSpec{s.port, s.chan + 1, "7i77-analog"});
    }
    for (const RemoteSpec &s : all) {
        std::string pc = std::to_string(s.port) + "." + std::to_string(s.chan);
        std::string tx = "SSerial " + std::to_string(s.port) + " TxData" + std::to_string(s.chan);
        std::string rx = "SSerial " + std::to_string(s.port) + " RxData" + std::to_string(s.chan);
        int t = find_pin(names, tx), r = find_pin(names, rx);
        if (t < 0 || r < 0) {
            err = "--sserial " + pc + "=" + s.type + ": firmware " + firmware + " has no pin \"" +
                  (t < 0 ? tx : rx) + "\" (Smart Serial port " + std::to_string(s.port) +
                  " channel " + std::to_string(s.chan) + ")";
            return false;
        }
        if (by_tx_[static_cast<size_t>(t)] >= 0) {
            err = "--sserial " + pc + ": that channel already has a remote";
            return false;
        }
        // serial numbers: distinct per channel, recognisable in status
        uint32_t unit = 0x76000000u | (s.port << 8) | s.chan;
        by_tx_[static_cast<size_t>(t)] = static_cast<int>(links_.size());
        links_.push_back(Entry{s, std::make_unique<Link>(static_cast<uint32_t>(t),
                                                         static_cast<uint32_t>(r), bit_ns,
                                                         make_personality(s.type, unit))});
    }
    return true;
}

void Remotes::attach(PinBank &pins, uint64_t now)
{
    pins_ = &pins;
    inner_ = pins.agent();
    if (by_tx_.size() < pins.size())
        by_tx_.resize(pins.size(), -1);
    for (Entry &e : links_) {
        pins.watch(e.link->tx_pin());
        pins.own(e.link->rx_pin(), true, now); // the line idles high
    }
    pins.set_agent(this);
}

uint64_t Remotes::next_event() const
{
    uint64_t n = inner_ ? inner_->next_event() : PinBank::kNever;
    for (const Entry &e : links_)
        n = std::min(n, e.link->next_event());
    return n;
}

void Remotes::run(uint64_t t)
{
    if (inner_ && inner_->next_event() <= t)
        inner_->run(t);
    for (Entry &e : links_)
        if (e.link->next_event() <= t)
            e.link->run(t, *pins_);
}

void Remotes::on_pin(uint32_t pin, bool level, uint64_t t)
{
    int i = pin < by_tx_.size() ? by_tx_[pin] : -1;
    if (i < 0) {
        if (inner_)
            inner_->on_pin(pin, level, t);
        return;
    }
    links_[static_cast<size_t>(i)].link->on_tx(level, t);
    pins_->agent_rescheduled();
}

std::string Remotes::entry_json(const Entry &e) const
{
    return "{\"channel\": \"" + std::to_string(e.spec.port) + "." + std::to_string(e.spec.chan) +
           "\", \"tx_pin\": " + std::to_string(e.link->tx_pin()) +
           ", \"rx_pin\": " + std::to_string(e.link->rx_pin()) + ", " + e.link->json() + ", " +
           e.link->board().json() + "}";
}

Remotes::Entry *Remotes::find(const std::string &pc)
{
    for (Entry &e : links_)
        if (pc == std::to_string(e.spec.port) + "." + std::to_string(e.spec.chan))
            return &e;
    return nullptr;
}

int Remotes::command(const std::string &cmd, uint64_t now, std::string &reply, std::string &err)
{
    std::vector<std::string> w = words(cmd);
    if (w.size() == 1 && w[0] == "status") {
        reply = "{\"remotes\": [";
        for (size_t i = 0; i < links_.size(); i++)
            reply += (i ? ", " : "") + entry_json(links_[i]);
        reply += "]}";
        return 0;
    }
    if (w.size() >= 3 && w[0] == "set") {
        Entry *e = find(w[1]);
        if (!e) {
            err = "SSERIAL: no remote on channel '" + w[1] + "' (vboard --sserial P.C=TYPE)";
            return -EINVAL;
        }
        std::vector<std::string> args(w.begin() + 2, w.end());
        if (args[0] == "plugged") {
            if (args.size() != 2 || (args[1] != "0" && args[1] != "1")) {
                err = "SSERIAL: want 'set P.C plugged 0|1'";
                return -EINVAL;
            }
            e->link->set_plugged(args[1] == "1", now, *pins_);
            pins_->agent_rescheduled();
        } else if (int r = e->link->board().set(args, err); r < 0) {
            err = "SSERIAL: " + err;
            return r;
        }
        reply = entry_json(*e);
        return 0;
    }
    err = "SSERIAL: unknown command '" + cmd +
          "' (status | set P.C plugged 0|1 | set P.C KEY VALUE...)";
    return -EINVAL;
}

} // namespace vb::sserial
