// SPDX-License-Identifier: GPL-2.0-or-later
//
// udp.cpp - the LBP16 UDP endpoint (udp.h).
#include "udp.h"

#include <algorithm>
#include <arpa/inet.h>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <netinet/in.h>
#include <sched.h>
#include <sys/socket.h>
#include <unistd.h>
#include <vector>

namespace vb::eth {

bool parse_udp_addr(const std::string &spec, uint32_t &ip, uint16_t &port, std::string &err)
{
    std::string host = spec;
    port = kLbp16Port;
    size_t colon = spec.find(':');
    if (colon != std::string::npos) {
        host = spec.substr(0, colon);
        std::string p = spec.substr(colon + 1);
        char *end = nullptr;
        unsigned long v = std::strtoul(p.c_str(), &end, 10);
        if (p.empty() || *end || v > 65535) {
            err = "bad --udp '" + spec + "': port must be 0..65535 (0: any free port)";
            return false;
        }
        port = static_cast<uint16_t>(v);
    }
    in_addr a{};
    if (host.empty() || inet_pton(AF_INET, host.c_str(), &a) != 1) {
        err = "bad --udp '" + spec + "': want an IPv4 address, optionally :PORT (127.0.0.2:27181)";
        return false;
    }
    ip = ntohl(a.s_addr);
    return true;
}

int serve_at_rt_priority(std::string &err)
{
    sched_param sp{};
    sp.sched_priority = 1;
    if (::sched_setscheduler(0, SCHED_FIFO, &sp) < 0) {
        int e = errno;
        err = std::string("--udp-rt: cannot switch to SCHED_FIFO priority 1: ") +
              std::strerror(e) + " (needs root, CAP_SYS_NICE or ulimit -r 1)";
        return -e;
    }
    return 0;
}

namespace {
// hm2_eth's servo-cycle read datagram: it writes the read sequence number
// to timer scratch 0x10 (command 0xD182, address 0x0010).
bool is_servo_read(const uint8_t *p, size_t n)
{
    static const uint8_t kSeqWrite[4] = {0x82, 0xD1, 0x10, 0x00};
    for (size_t i = 0; i + 4 <= n; i += 2)
        if (std::memcmp(p + i, kSeqWrite, 4) == 0)
            return true;
    return false;
}
} // namespace

UdpEndpoint::UdpEndpoint(EthBoard &board, bool log) : board_(board), log_(log)
{
}

UdpEndpoint::~UdpEndpoint()
{
    if (fd_ >= 0)
        ::close(fd_);
}

int UdpEndpoint::open(uint32_t ip, uint16_t port, std::string &err)
{
    int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (fd < 0) {
        err = std::string("socket(AF_INET, SOCK_DGRAM): ") + std::strerror(errno);
        return -errno;
    }
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_port = htons(port);
    sa.sin_addr.s_addr = htonl(ip);
    if (::bind(fd, reinterpret_cast<sockaddr *>(&sa), sizeof sa) < 0) {
        int e = errno;
        char b[INET_ADDRSTRLEN];
        inet_ntop(AF_INET, &sa.sin_addr, b, sizeof b);
        err = std::string("cannot listen for LBP16 on UDP ") + b + ":" + std::to_string(port) +
              ": " + std::strerror(e);
        ::close(fd);
        return -e;
    }
    socklen_t len = sizeof sa;
    ::getsockname(fd, reinterpret_cast<sockaddr *>(&sa), &len);
    port_ = ntohs(sa.sin_port);
    fd_ = fd;
    return 0;
}

void UdpEndpoint::on_readable()
{
    uint8_t buf[65536];
    std::vector<uint8_t> reply;
    for (;;) {
        sockaddr_in from{};
        socklen_t flen = sizeof from;
        ssize_t n = ::recvfrom(fd_, buf, sizeof buf, 0, reinterpret_cast<sockaddr *>(&from), &flen);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return; // EAGAIN: drained
        }
        if (tick_ns_ && is_servo_read(buf, static_cast<size_t>(n)))
            board_.run_until(board_.now_ns() + tick_ns_);
        bool send = board_.lbp16(buf, static_cast<size_t>(n), reply);
        if (log_) {
            char hex[3 * 24 + 4] = "";
            size_t shown = std::min<size_t>(static_cast<size_t>(n), 24);
            for (size_t i = 0; i < shown; i++)
                std::snprintf(hex + 3 * i, 4, " %02x", buf[i]);
            std::fprintf(stderr, "vboard: LBP16 %zd bytes from %s:%u [%s%s] -> %s%s @%llu ns\n", n,
                         inet_ntoa(from.sin_addr), ntohs(from.sin_port), hex + 1,
                         shown < static_cast<size_t>(n) ? " ..." : "",
                         send ? std::to_string(reply.size()).c_str() : "no",
                         send ? " bytes" : (" reply " + board_.engine().last_error()).c_str(),
                         static_cast<unsigned long long>(board_.now_ns()));
        }
        if (!send)
            continue;
        ssize_t s = ::sendto(fd_, reply.data(), reply.size(), 0,
                             reinterpret_cast<sockaddr *>(&from), flen);
        board_.engine().count_tx(s == static_cast<ssize_t>(reply.size()));
    }
}

} // namespace vb::eth
