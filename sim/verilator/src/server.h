// SPDX-License-Identifier: GPL-2.0-or-later
//
// server.h - the vboard socket server: framing, epochs, free-running time,
// request dispatch to a Board (docs/vboard-protocol.md).
#ifndef VBOARD_SERVER_H
#define VBOARD_SERVER_H

#include <cstdint>
#include <string>
#include <vector>

#include "board.h"

namespace vb::plant {
class Machine;
}
namespace vb::sserial {
class Remotes;
}

namespace vb {

// Another event source the poll loop serves (a virtual Ethernet board's UDP
// endpoint, sim/verilator/eth/udp.h).
class FdHandler {
  public:
    virtual ~FdHandler() = default;
    virtual int fd() const = 0;
    virtual void on_readable() = 0;
};

struct ServerOptions {
    std::string socket_path;
    // Permission bits of the socket file, set explicitly (not from the
    // umask): only the owner may connect unless asked (--socket-mode).
    unsigned socket_mode = 0600;
    bool freerun = false;
    bool log = false;
    // After a request, keep polling without sleeping for this long: the next
    // request of a servo cycle usually follows at once, and waking a
    // sleeping process costs tens of us on some machines.  0 = never spin.
    unsigned spin_us = 0;
    // Free-running: board time run per step, and wall time spent running
    // before the sockets are looked at again (a board slower than real time
    // still answers within about one budget).
    uint64_t freerun_slice_ns = 100000;
    uint64_t freerun_budget_ns = 2000000;
};

class Server {
  public:
    Server(Board &board, const ServerOptions &opt);
    ~Server();
    Server(const Server &) = delete;
    Server &operator=(const Server &) = delete;

    // Bind and listen; -errno with the reason in err.
    int open(std::string &err);
    // Serve until SIGTERM/SIGINT (blocked by the caller and passed as a
    // signalfd).  Returns the exit status.
    int run(int signal_fd);
    // Serve the requests in `bytes` as one connection's input (a trailing
    // partial request is dropped); replies go to `fd`, a connected stream
    // socket the caller drains.  false when the connection would be closed.
    // For the protocol fuzz target: the same path as bytes from a socket.
    bool serve_bytes(int fd, const uint8_t *bytes, size_t n);
    // The machine behind the pins (vboard --machine): VB_PLANT requests and
    // one trace point per host request.
    void set_plant(plant::Machine *m) { plant_ = m; }
    // The Smart Serial remotes (vboard --sserial): VB_SSERIAL requests.
    void set_sserial(sserial::Remotes *r) { sserial_ = r; }
    // Serve `h` from the poll loop too (not owned; must outlive run()).
    void add_handler(FdHandler *h) { handlers_.push_back(h); }

  private:
    struct Conn {
        int fd;
        unsigned id;
        std::vector<uint8_t> rx;
        bool have_epoch = false;
        int64_t epoch = 0;
    };
    struct Reply {
        int status = 0;
        std::vector<uint8_t> data;
        bool close = false;
    };

    void accept_client();
    // false: the connection is gone (closed or must be closed).
    bool on_readable(Conn &c);
    bool process(Conn &c);
    Reply dispatch(Conn &c, const vb_header &h, const uint8_t *p, size_t n);
    // false (and the reply in r) when the host time jumps further ahead
    // than one request may advance the board.
    bool advance_lockstep(Conn &c, uint64_t host_time, Reply &r);
    void run_board(uint64_t t);
    void freerun_step(uint64_t budget_ns);
    bool send_reply(Conn &c, const vb_header &req, const Reply &r);
    void close_conn(size_t idx);
    uint64_t wall_ns() const;

    Reply r_hello();
    Reply r_read(const uint8_t *p, size_t n);
    Reply r_write(const uint8_t *p, size_t n);
    Reply r_config(const uint8_t *p, size_t n);
    Reply r_jtag(const uint8_t *p, size_t n);
    Reply r_time(const uint8_t *p, size_t n);
    Reply r_probe(const uint8_t *p, size_t n, bool reset);
    Reply r_drive(const uint8_t *p, size_t n);
    Reply r_quad(const uint8_t *p, size_t n);
    Reply r_loop(const uint8_t *p, size_t n);
    Reply r_dump(const uint8_t *p, size_t n);
    Reply r_epp(const uint8_t *p, size_t n);
    Reply r_stall(const uint8_t *p, size_t n);
    Reply r_plant(const uint8_t *p, size_t n);
    Reply r_sserial(const uint8_t *p, size_t n);

    Board &board_;
    ServerOptions opt_;
    int listen_fd_ = -1;
    std::vector<Conn> conns_;
    unsigned next_id_ = 1;
    bool lockstep_;
    uint64_t fr_wall0_ = 0, fr_board0_ = 0; // free-running reference point
    int signal_fd_ = -1;
    bool stopping_ = false; // a signal arrived while a request ran
    plant::Machine *plant_ = nullptr;
    sserial::Remotes *sserial_ = nullptr;
    std::vector<FdHandler *> handlers_;
    // A datagram waits on a handler's fd: free-running stops to serve it
    // (a board slower than real time would otherwise answer a slice late).
    bool handler_input() const;
};

// Error reply helper.
std::vector<uint8_t> msg_bytes(const std::string &s);

} // namespace vb

#endif // VBOARD_SERVER_H
