// SPDX-License-Identifier: GPL-2.0-or-later
//
// udp.h - the UDP endpoint of a virtual Ethernet board: LBP16 datagrams on
// ADDR:PORT (default 127.0.0.1:27181), served from the vboard's poll loop
// (server.h FdHandler).  Replies go to the sender's address and port.
#ifndef VBOARD_ETH_UDP_H
#define VBOARD_ETH_UDP_H

#include <cstdint>
#include <string>

#include "eth_board.h"
#include "server.h"

namespace vb::eth {

constexpr uint16_t kLbp16Port = 27181;

// "127.0.0.2", "127.0.0.2:27181" -> address (host order) and port; false
// with a message for anything else.
bool parse_udp_addr(const std::string &spec, uint32_t &ip, uint16_t &port, std::string &err);

// vboard --udp-rt: the calling thread (the server loop) goes to SCHED_FIFO
// priority 1, so a datagram is answered within microseconds whatever else
// the machine runs.  Stock mesaflash needs that on a loaded machine: its
// probe reads the IDROM cookie, sleeps 2 ms and looks once (non-blocking)
// for the reply; a responder at normal priority waiting for a CPU misses
// that window ("No 7I96S board found").  Only for a free-running board,
// whose loop sleeps between short slices.  -errno with a message (needs
// root, CAP_SYS_NICE or an RLIMIT_RTPRIO of at least 1).
int serve_at_rt_priority(std::string &err);

class UdpEndpoint final : public FdHandler {
  public:
    UdpEndpoint(EthBoard &board, bool log);
    ~UdpEndpoint() override;
    UdpEndpoint(const UdpEndpoint &) = delete;
    UdpEndpoint &operator=(const UdpEndpoint &) = delete;

    int open(uint32_t ip, uint16_t port, std::string &err);
    // Lockstep over UDP (vboard --udp-tick): a servo-cycle read datagram
    // (one that writes the read sequence number to timer scratch 0x10, as
    // hm2_eth does every period) first runs the board tick_ns further;
    // other datagrams find the board where it is.  0: the board free-runs.
    void set_tick_ns(uint64_t ns) { tick_ns_ = ns; }
    int fd() const override { return fd_; }
    // The port bound (the one asked for, or the kernel's pick for 0).
    uint16_t port() const { return port_; }
    void on_readable() override;

  private:
    EthBoard &board_;
    bool log_;
    int fd_ = -1;
    uint16_t port_ = 0;
    uint64_t tick_ns_ = 0;
};

} // namespace vb::eth

#endif // VBOARD_ETH_UDP_H
