// SPDX-License-Identifier: GPL-2.0-or-later
//
// server.cpp - the vboard socket server (server.h, docs/vboard-protocol.md).
#include "server.h"

#include "plant/machine.h"
#include "sserial/remotes.h"
#include "vcd2fst.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

#include <fcntl.h>
#include <poll.h>
#include <sys/signalfd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

namespace vb {

namespace {
constexpr size_t kHdr = sizeof(vb_header);
constexpr uint32_t kLbWindow = 0x10000;   // the hm2 address space (64 KiB)
constexpr int kSendTimeoutMs = 5000;      // a client that does not read its replies is dropped
constexpr uint64_t kFreerunMaxLagNs = 50000000; // behind by more: re-base (run as fast as we can)
// One request may advance the board by at most this much board time (a
// servo period is ~1 ms): a client's bad time stamp must not keep the board
// simulating for hours while every other client waits.
constexpr uint64_t kMaxAdvanceNs = 60ull * 1000000000ull;

const char *type_name(uint16_t t)
{
    switch (t) {
    case VB_HELLO: return "HELLO";
    case VB_READ: return "READ";
    case VB_WRITE: return "WRITE";
    case VB_EPP: return "EPP";
    case VB_EPP_STALL: return "EPP_STALL";
    case VB_CONFIG: return "CONFIG";
    case VB_TIME: return "TIME";
    case VB_PROBE: return "PROBE";
    case VB_DRIVE: return "DRIVE";
    case VB_QUAD: return "QUAD";
    case VB_LOOP: return "LOOP";
    case VB_PROBE_RESET: return "PROBE_RESET";
    case VB_DUMP: return "DUMP";
    case VB_PLANT: return "PLANT";
    case VB_SSERIAL: return "SSERIAL";
    case VB_JTAG: return "JTAG";
    default: return "?";
    }
}

template <class T> T load(const uint8_t *p)
{
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

template <class T> void append(std::vector<uint8_t> &out, const T &v)
{
    const uint8_t *b = reinterpret_cast<const uint8_t *>(&v);
    out.insert(out.end(), b, b + sizeof v);
}
} // namespace

std::vector<uint8_t> msg_bytes(const std::string &s) { return {s.begin(), s.end()}; }

#define VB_FAIL(code, text)                                                                        \
    do {                                                                                           \
        Reply r_;                                                                                  \
        r_.status = (code);                                                                        \
        r_.data = msg_bytes(text);                                                                 \
        return r_;                                                                                 \
    } while (0)

Server::Server(Board &board, const ServerOptions &opt)
    : board_(board), opt_(opt), lockstep_(!opt.freerun)
{
}

Server::~Server()
{
    for (Conn &c : conns_)
        ::close(c.fd);
    if (listen_fd_ >= 0) {
        ::close(listen_fd_);
        ::unlink(opt_.socket_path.c_str());
    }
}

uint64_t Server::wall_ns() const
{
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<uint64_t>(ts.tv_sec) * 1000000000ull + static_cast<uint64_t>(ts.tv_nsec);
}

int Server::open(std::string &err)
{
    sockaddr_un sa{};
    sa.sun_family = AF_UNIX;
    if (opt_.socket_path.empty() || opt_.socket_path.size() >= sizeof sa.sun_path) {
        err = "socket path '" + opt_.socket_path + "' is empty or longer than " +
              std::to_string(sizeof sa.sun_path - 1) + " bytes";
        return -EINVAL;
    }
    std::memcpy(sa.sun_path, opt_.socket_path.c_str(), opt_.socket_path.size() + 1);
    int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        err = std::string("socket(): ") + std::strerror(errno);
        return -errno;
    }
    // A socket file left by a dead vboard is removed; a live one is not
    // taken over.
    struct stat st;
    if (::lstat(sa.sun_path, &st) == 0) {
        if (!S_ISSOCK(st.st_mode)) {
            err = opt_.socket_path + " exists and is not a socket";
            ::close(fd);
            return -EEXIST;
        }
        if (::connect(fd, reinterpret_cast<sockaddr *>(&sa), sizeof sa) == 0) {
            err = opt_.socket_path + " is in use by another running board";
            ::close(fd);
            return -EADDRINUSE;
        }
        ::close(fd);
        ::unlink(sa.sun_path);
        fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (fd < 0) {
            err = std::string("socket(): ") + std::strerror(errno);
            return -errno;
        }
    }
    // Created owner-only whatever the umask (no window in which another user
    // could connect), then given the requested mode.
    mode_t old_umask = ::umask(0177);
    int br = ::bind(fd, reinterpret_cast<sockaddr *>(&sa), sizeof sa);
    int be = errno;
    ::umask(old_umask);
    if (br < 0 || ::chmod(sa.sun_path, static_cast<mode_t>(opt_.socket_mode)) < 0 ||
        ::listen(fd, 8) < 0) {
        int e = br < 0 ? be : errno;
        err = "cannot listen on " + opt_.socket_path + ": " + std::strerror(e);
        if (br == 0)
            ::unlink(sa.sun_path);
        ::close(fd);
        return -e;
    }
    listen_fd_ = fd;
    return 0;
}

void Server::accept_client()
{
    int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
    if (fd < 0)
        return;
    Conn c;
    c.fd = fd;
    c.id = next_id_++;
    conns_.push_back(std::move(c));
    if (opt_.log)
        std::fprintf(stderr, "vboard: client %u connected\n", conns_.back().id);
}

void Server::close_conn(size_t idx)
{
    if (opt_.log)
        std::fprintf(stderr, "vboard: client %u disconnected\n", conns_[idx].id);
    ::close(conns_[idx].fd);
    conns_.erase(conns_.begin() + static_cast<long>(idx));
}

bool Server::on_readable(Conn &c)
{
    uint8_t buf[65536];
    for (;;) {
        ssize_t n = ::recv(c.fd, buf, sizeof buf, 0);
        if (n > 0) {
            c.rx.insert(c.rx.end(), buf, buf + n);
            // Serve what came before reading more: a client streaming
            // requests cannot keep the board in this loop or grow rx
            // without bound (the rest waits in the socket).
            if (c.rx.size() >= kHdr + VB_MAX_PAYLOAD)
                return process(c);
            continue;
        }
        if (n == 0)
            return process(c) && false; // peer closed: serve what came, then drop
        if (errno == EINTR)
            continue;
        if (errno == EAGAIN || errno == EWOULDBLOCK)
            return process(c);
        return false;
    }
}

bool Server::process(Conn &c)
{
    size_t off = 0;
    bool alive = true;
    while (alive && c.rx.size() - off >= kHdr) {
        vb_header h = load<vb_header>(&c.rx[off]);
        if (h.magic != VB_REQ_MAGIC) {
            Reply r;
            r.status = -EPROTO;
            char b[120];
            std::snprintf(b, sizeof b,
                          "bad request magic 0x%08x (want 0x%08x \"VBRQ\"); closing the connection",
                          h.magic, VB_REQ_MAGIC);
            r.data = msg_bytes(b);
            send_reply(c, h, r);
            return false;
        }
        if (h.length > VB_MAX_PAYLOAD) {
            Reply r;
            r.status = -EINVAL;
            r.data = msg_bytes("request payload of " + std::to_string(h.length) +
                               " bytes is over the limit of " + std::to_string(VB_MAX_PAYLOAD) +
                               "; closing the connection");
            send_reply(c, h, r);
            return false;
        }
        if (c.rx.size() - off < kHdr + h.length)
            break;
        Reply r = dispatch(c, h, &c.rx[off + kHdr], h.length);
        if (opt_.log)
            std::fprintf(stderr, "vboard: client %u %s seq %u len %u -> %d @%llu ns%s%.*s\n", c.id,
                         type_name(h.type), h.seq, h.length, r.status,
                         static_cast<unsigned long long>(board_.now_ns()),
                         r.status < 0 ? ": " : "", r.status < 0 ? static_cast<int>(r.data.size()) : 0,
                         r.status < 0 ? reinterpret_cast<const char *>(r.data.data()) : "");
        alive = send_reply(c, h, r) && !r.close;
        off += kHdr + h.length;
    }
    c.rx.erase(c.rx.begin(), c.rx.begin() + static_cast<long>(off));
    return alive;
}

bool Server::serve_bytes(int fd, const uint8_t *bytes, size_t n)
{
    Conn c{fd, next_id_++, {}};
    c.rx.assign(bytes, bytes + n);
    return process(c);
}

bool Server::send_reply(Conn &c, const vb_header &req, const Reply &r)
{
    vb_header h{};
    h.magic = VB_REP_MAGIC;
    h.type = req.type;
    h.status = static_cast<int16_t>(r.status);
    h.length = static_cast<uint32_t>(r.data.size());
    h.seq = req.seq;
    h.time_ns = board_.now_ns();
    std::vector<uint8_t> out;
    out.reserve(kHdr + r.data.size());
    append(out, h);
    out.insert(out.end(), r.data.begin(), r.data.end());
    size_t done = 0;
    while (done < out.size()) {
        ssize_t n = ::send(c.fd, out.data() + done, out.size() - done, MSG_NOSIGNAL);
        if (n > 0) {
            done += static_cast<size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            pollfd p{c.fd, POLLOUT, 0};
            if (::poll(&p, 1, kSendTimeoutMs) > 0)
                continue;
        }
        return false; // gone (EPIPE, ECONNRESET) or not reading
    }
    return true;
}

void Server::run_board(uint64_t t)
{
    // Long runs go in slices with a look at the signal fd in between, so a
    // SIGTERM ends even a request that would simulate minutes of wall time.
    constexpr uint64_t kSliceNs = 200000;
    while (board_.now_ns() < t && !stopping_) {
        board_.run_until(std::min(t, board_.now_ns() + kSliceNs));
        pollfd p{signal_fd_, POLLIN, 0};
        if (signal_fd_ >= 0 && ::poll(&p, 1, 0) > 0)
            stopping_ = true;
    }
}

static std::string too_far(uint64_t ns, const char *what)
{
    char b[200];
    std::snprintf(b, sizeof b,
                  "%s of %.3f s is more than one request may advance the board (%.0f s); the "
                  "board's time is unchanged",
                  what, static_cast<double>(ns) * 1e-9, static_cast<double>(kMaxAdvanceNs) * 1e-9);
    return b;
}

bool Server::advance_lockstep(Conn &c, uint64_t host_time, Reply &r)
{
    if (!lockstep_ || host_time == 0)
        return true;
    if (!c.have_epoch) {
        // Board time continues where it is: this host time is "now".
        // (modulo 2^64: any 64-bit host time is allowed, no signed overflow)
        c.epoch = static_cast<int64_t>(host_time - board_.now_ns());
        c.have_epoch = true;
        return true;
    }
    int64_t target = static_cast<int64_t>(host_time - static_cast<uint64_t>(c.epoch));
    if (target <= 0 || static_cast<uint64_t>(target) <= board_.now_ns())
        return true;
    uint64_t jump = static_cast<uint64_t>(target) - board_.now_ns();
    if (jump > kMaxAdvanceNs) {
        r.status = -ERANGE;
        r.data = msg_bytes(too_far(jump, "the host time jump") +
                           "; the next request re-takes this connection's epoch");
        c.have_epoch = false;
        return false;
    }
    run_board(static_cast<uint64_t>(target));
    return true;
}

Server::Reply Server::dispatch(Conn &c, const vb_header &h, const uint8_t *p, size_t n)
{
    Reply jumped;
    if (!advance_lockstep(c, h.time_ns, jumped))
        return jumped;
    if (plant_ && lockstep_)
        plant_->on_request(h.time_ns, board_.now_ns());
    switch (h.type) {
    case VB_HELLO: return r_hello();
    case VB_READ: return r_read(p, n);
    case VB_WRITE: return r_write(p, n);
    case VB_EPP: return r_epp(p, n);
    case VB_EPP_STALL: return r_stall(p, n);
    case VB_CONFIG: return r_config(p, n);
    case VB_TIME: return r_time(p, n);
    case VB_PROBE: return r_probe(p, n, false);
    case VB_PROBE_RESET: return r_probe(p, n, true);
    case VB_DRIVE: return r_drive(p, n);
    case VB_QUAD: return r_quad(p, n);
    case VB_LOOP: return r_loop(p, n);
    case VB_DUMP: return r_dump(p, n);
    case VB_PLANT: return r_plant(p, n);
    case VB_SSERIAL: return r_sserial(p, n);
    case VB_JTAG: return r_jtag(p, n);
    default: {
        char b[80];
        std::snprintf(b, sizeof b, "unknown request type 0x%02x", h.type);
        VB_FAIL(-EINVAL, b);
    }
    }
}

Server::Reply Server::r_hello()
{
    vb_hello v{};
    v.version = VB_PROTO_VERSION;
    v.bus = board_.bus();
    v.state = board_.configured() ? VB_STATE_CONFIGURED : VB_STATE_BLANK;
    v.io_pins = board_.pins().size();
    v.clock_low_hz = board_.clock_low_hz();
    v.clock_high_hz = board_.clock_high_hz();
    v.lockstep = lockstep_ ? 1 : 0;
    std::strncpy(v.board, board_.name().c_str(), sizeof v.board - 1);
    std::strncpy(v.firmware, board_.firmware().c_str(), sizeof v.firmware - 1);
    std::strncpy(v.fpga_part, board_.fpga_part().c_str(), sizeof v.fpga_part - 1);
    Reply r;
    append(r.data, v);
    return r;
}

namespace {
// Checks one local-bus transfer; "" when fine.
std::string check_xfer(const vb_xfer &x, const char *what)
{
    char b[160];
    if (x.addr % 4 || x.size % 4) {
        std::snprintf(b, sizeof b,
                      "%s of %u bytes at 0x%x: address and size must be multiples of 4", what,
                      x.size, x.addr);
        return b;
    }
    if (x.addr >= kLbWindow || x.size > kLbWindow - x.addr) {
        std::snprintf(b, sizeof b,
                      "%s of %u bytes at 0x%x runs outside the 64 KiB hm2 window", what, x.size,
                      x.addr);
        return b;
    }
    return "";
}
} // namespace

Server::Reply Server::r_read(const uint8_t *p, size_t n)
{
    if (n % sizeof(vb_xfer))
        VB_FAIL(-EPROTO, "READ payload of " + std::to_string(n) +
                             " bytes is not a list of 8-byte transfers");
    size_t cnt = n / sizeof(vb_xfer);
    std::vector<vb_xfer> x(cnt);
    uint64_t total = 0;
    for (size_t i = 0; i < cnt; i++) {
        x[i] = load<vb_xfer>(p + i * sizeof(vb_xfer));
        std::string e = check_xfer(x[i], "read");
        if (!e.empty())
            VB_FAIL(-EINVAL, e);
        total += x[i].size;
    }
    if (total > VB_MAX_PAYLOAD)
        VB_FAIL(-EINVAL, "read of " + std::to_string(total) + " bytes is over the reply limit");
    Reply r;
    std::string err;
    r.status = board_.lb_read(x.data(), cnt, r.data, err);
    if (r.status < 0)
        r.data = msg_bytes(err);
    return r;
}

Server::Reply Server::r_write(const uint8_t *p, size_t n)
{
    std::vector<vb_xfer> x;
    std::vector<uint8_t> data;
    size_t off = 0;
    while (off < n) {
        if (n - off < sizeof(vb_xfer))
            VB_FAIL(-EPROTO, "WRITE payload ends inside a transfer header (at byte " +
                                 std::to_string(off) + ")");
        vb_xfer v = load<vb_xfer>(p + off);
        off += sizeof v;
        std::string e = check_xfer(v, "write");
        if (!e.empty())
            VB_FAIL(-EINVAL, e);
        if (n - off < v.size)
            VB_FAIL(-EPROTO, "WRITE payload is shorter than its transfer of " +
                                 std::to_string(v.size) + " bytes");
        data.insert(data.end(), p + off, p + off + v.size);
        off += v.size;
        x.push_back(v);
    }
    Reply r;
    std::string err;
    r.status = board_.lb_write(x.data(), x.size(), data.data(), err);
    if (r.status < 0)
        r.data = msg_bytes(err);
    return r;
}

Server::Reply Server::r_config(const uint8_t *p, size_t n)
{
    if (n < sizeof(vb_config))
        VB_FAIL(-EPROTO, "CONFIG payload of " + std::to_string(n) + " bytes is shorter than 8");
    vb_config cfg = load<vb_config>(p);
    if (cfg.op != VB_CONFIG_PROGRAM && n != sizeof cfg)
        VB_FAIL(-EPROTO, "CONFIG status/reset carries no bitstream");
    vb_config_status st{};
    std::string err;
    Reply r;
    r.status = board_.config(cfg.op, p + sizeof cfg, n - sizeof cfg, st, err);
    if (r.status < 0) {
        r.data = msg_bytes(err);
        if (opt_.log || cfg.op == VB_CONFIG_PROGRAM)
            std::fprintf(stderr, "vboard: %s\n", err.c_str());
    } else {
        append(r.data, st);
    }
    return r;
}

Server::Reply Server::r_time(const uint8_t *p, size_t n)
{
    if (n != sizeof(vb_time))
        VB_FAIL(-EPROTO, "TIME payload of " + std::to_string(n) + " bytes, want 16");
    vb_time t = load<vb_time>(p);
    switch (t.op) {
    case VB_TIME_ADVANCE:
        if (t.ns > kMaxAdvanceNs)
            VB_FAIL(-ERANGE, too_far(t.ns, "a TIME advance"));
        run_board(board_.now_ns() + t.ns);
        break;
    case VB_TIME_LOCKSTEP:
        lockstep_ = true;
        for (Conn &c : conns_)
            c.have_epoch = false;
        break;
    case VB_TIME_FREERUN:
        lockstep_ = false;
        fr_wall0_ = wall_ns();
        fr_board0_ = board_.now_ns();
        break;
    default:
        VB_FAIL(-EINVAL, "TIME: unknown operation " + std::to_string(t.op) +
                             " (0 advance, 1 lockstep, 2 free-run)");
    }
    return {};
}

Server::Reply Server::r_probe(const uint8_t *p, size_t n, bool reset)
{
    if (n != 8)
        VB_FAIL(-EPROTO, std::string(reset ? "PROBE_RESET" : "PROBE") + " payload of " +
                             std::to_string(n) + " bytes, want 8 (first, count)");
    uint32_t first = load<uint32_t>(p), count = load<uint32_t>(p + 4);
    Reply r;
    std::string err;
    if (reset) {
        r.status = board_.pins().probe_reset(first, count, board_.now_ns(), err);
    } else {
        std::vector<vb_pin> pins;
        r.status = board_.pins().probe(first, count, board_.now_ns(), pins, err);
        if (r.status == 0)
            for (const vb_pin &v : pins)
                append(r.data, v);
    }
    if (r.status < 0)
        r.data = msg_bytes(err);
    return r;
}

Server::Reply Server::r_drive(const uint8_t *p, size_t n)
{
    if (n % sizeof(vb_drive))
        VB_FAIL(-EPROTO, "DRIVE payload of " + std::to_string(n) +
                             " bytes is not a list of 8-byte entries");
    size_t cnt = n / sizeof(vb_drive);
    PinBank &pins = board_.pins();
    for (size_t i = 0; i < cnt; i++) { // all or nothing
        vb_drive d = load<vb_drive>(p + i * sizeof d);
        if (d.pin >= pins.size())
            VB_FAIL(-EINVAL, "drive: I/O pin " + std::to_string(d.pin) +
                                 " does not exist (this board has " +
                                 std::to_string(pins.size()) + " pins)");
        if (d.mode > VB_DRIVE_HIGH)
            VB_FAIL(-EINVAL, "drive: I/O pin " + std::to_string(d.pin) + ": mode " +
                                 std::to_string(d.mode) +
                                 " is not release (0), low (1) or high (2)");
    }
    std::string err;
    for (size_t i = 0; i < cnt; i++) {
        vb_drive d = load<vb_drive>(p + i * sizeof d);
        pins.drive(d.pin, d.mode, board_.now_ns(), err);
    }
    return {};
}

Server::Reply Server::r_quad(const uint8_t *p, size_t n)
{
    if (n != sizeof(vb_quad))
        VB_FAIL(-EPROTO, "QUAD payload of " + std::to_string(n) + " bytes, want " +
                             std::to_string(sizeof(vb_quad)));
    Reply r;
    std::string err;
    r.status = board_.pins().quad(load<vb_quad>(p), board_.now_ns(), err);
    if (r.status < 0)
        r.data = msg_bytes(err);
    return r;
}

Server::Reply Server::r_loop(const uint8_t *p, size_t n)
{
    if (n % sizeof(vb_loop))
        VB_FAIL(-EPROTO, "LOOP payload of " + std::to_string(n) +
                             " bytes is not a list of 16-byte entries");
    size_t cnt = n / sizeof(vb_loop);
    PinBank &pins = board_.pins();
    for (size_t i = 0; i < cnt; i++) {
        vb_loop l = load<vb_loop>(p + i * sizeof l);
        if (l.from >= pins.size() || (l.to != UINT32_MAX && l.to >= pins.size()))
            VB_FAIL(-EINVAL, "loop " + std::to_string(l.from) + " -> " + std::to_string(l.to) +
                                 ": pin does not exist (this board has " +
                                 std::to_string(pins.size()) + " pins)");
        if (l.from == l.to)
            VB_FAIL(-EINVAL, "loop: I/O pin " + std::to_string(l.from) +
                                 " cannot be looped into itself");
    }
    std::string err;
    for (size_t i = 0; i < cnt; i++) {
        vb_loop l = load<vb_loop>(p + i * sizeof l);
        pins.loop(l.from, l.to, l.invert != 0, board_.now_ns(), err);
    }
    return {};
}

Server::Reply Server::r_dump(const uint8_t *p, size_t n)
{
    if (n < 4)
        VB_FAIL(-EPROTO, "DUMP payload of " + std::to_string(n) + " bytes, want u32 on + path");
    uint32_t on = load<uint32_t>(p);
    std::string path(reinterpret_cast<const char *>(p + 4), n - 4);
    if (on) {
        if (path.empty() || path.find('\0') != std::string::npos)
            VB_FAIL(-EINVAL, "DUMP needs a file path (without NUL bytes)");
        if (path.size() >= 4 && path.compare(path.size() - 4, 4, ".fst") == 0 && !have_fst())
            VB_FAIL(-ENOTSUP, "dump " + path +
                                  ": this vboard was built without FST support (liblz4-dev "
                                  "missing); use a .vcd path");
    }
    Reply r;
    std::string err;
    r.status = board_.dump(on != 0, path, err);
    if (r.status < 0)
        r.data = msg_bytes(err);
    return r;
}

Server::Reply Server::r_plant(const uint8_t *p, size_t n)
{
    if (!plant_)
        VB_FAIL(-ENOTSUP, "PLANT: no machine is attached to this board (vboard --machine FILE)");
    std::string cmd(reinterpret_cast<const char *>(p), n);
    if (cmd.find('\0') != std::string::npos)
        VB_FAIL(-EINVAL, "PLANT: the command contains a NUL byte");
    Reply r;
    std::string reply, err;
    r.status = plant_->command(cmd, board_.now_ns(), reply, err);
    r.data = r.status < 0 ? msg_bytes(err) : std::vector<uint8_t>(reply.begin(), reply.end());
    return r;
}

Server::Reply Server::r_sserial(const uint8_t *p, size_t n)
{
    if (!sserial_)
        VB_FAIL(-ENOTSUP, "SSERIAL: no Smart Serial remote on this board (vboard --sserial P.C=TYPE)");
    std::string cmd(reinterpret_cast<const char *>(p), n);
    if (cmd.find('\0') != std::string::npos)
        VB_FAIL(-EINVAL, "SSERIAL: the command contains a NUL byte");
    Reply r;
    std::string reply, err;
    r.status = sserial_->command(cmd, board_.now_ns(), reply, err);
    r.data = r.status < 0 ? msg_bytes(err) : std::vector<uint8_t>(reply.begin(), reply.end());
    return r;
}

Server::Reply Server::r_jtag(const uint8_t *p, size_t n)
{
    if (n != 4)
        VB_FAIL(-EPROTO, "JTAG payload of " + std::to_string(n) + " bytes, want 4");
    Reply r;
    std::string err;
    uint32_t tdo = 0;
    r.status = board_.jtag(load<uint32_t>(p), tdo, err);
    if (r.status < 0)
        r.data = msg_bytes(err);
    else
        append(r.data, tdo);
    return r;
}

Server::Reply Server::r_epp(const uint8_t *p, size_t n)
{
    Reply r;
    std::string err;
    r.status = board_.epp(p, n, r.data, err);
    if (r.status < 0)
        r.data = msg_bytes(err);
    return r;
}

Server::Reply Server::r_stall(const uint8_t *p, size_t n)
{
    if (n != 4)
        VB_FAIL(-EPROTO, "EPP_STALL payload of " + std::to_string(n) + " bytes, want 4");
    Reply r;
    std::string err;
    r.status = board_.epp_stall(load<uint32_t>(p) != 0, err);
    if (r.status < 0)
        r.data = msg_bytes(err);
    return r;
}

void Server::freerun_step(uint64_t budget_ns)
{
    uint64_t wall0 = wall_ns();
    for (;;) {
        uint64_t now = board_.now_ns();
        uint64_t target = fr_board0_ + (wall_ns() - fr_wall0_);
        if (target <= now)
            return;
        if (target - now > kFreerunMaxLagNs) {
            // Slower than real time: keep running as fast as we can, but do
            // not try to catch up on time we could never make up.
            fr_wall0_ = wall_ns();
            fr_board0_ = now;
            target = now + opt_.freerun_slice_ns;
        }
        board_.run_until(std::min(target, now + opt_.freerun_slice_ns));
        if (wall_ns() - wall0 > budget_ns || handler_input())
            return;
    }
}

bool Server::handler_input() const
{
    if (handlers_.empty())
        return false;
    pollfd pf[4];
    nfds_t n = 0;
    for (const FdHandler *h : handlers_)
        if (n < 4)
            pf[n++] = {h->fd(), POLLIN, 0};
    return ::poll(pf, n, 0) > 0;
}

int Server::run(int signal_fd)
{
    signal_fd_ = signal_fd;
    if (!lockstep_) {
        fr_wall0_ = wall_ns();
        fr_board0_ = board_.now_ns();
    }
    uint64_t spin_until = 0;
    for (;;) {
        std::vector<pollfd> pf;
        pf.push_back({signal_fd, POLLIN, 0});
        pf.push_back({listen_fd_, POLLIN, 0});
        for (const FdHandler *h : handlers_)
            pf.push_back({h->fd(), POLLIN, 0});
        const size_t first_conn = 2 + handlers_.size();
        for (const Conn &c : conns_)
            pf.push_back({c.fd, POLLIN, 0});
        bool spinning = opt_.spin_us && wall_ns() < spin_until;
        int rc = ::poll(pf.data(), pf.size(), spinning ? 0 : lockstep_ ? -1 : 1);
        if (rc < 0 && errno != EINTR) {
            std::fprintf(stderr, "vboard: poll: %s\n", std::strerror(errno));
            return 1;
        }
        if (rc > 0 && (pf[0].revents & POLLIN)) {
            signalfd_siginfo si;
            if (::read(signal_fd, &si, sizeof si) == sizeof si && opt_.log)
                std::fprintf(stderr, "vboard: signal %u, exiting\n", si.ssi_signo);
            return 0;
        }
        if (rc > 0) {
            // Clients first (their fds follow the listener), highest index
            // first so closing one does not shift the others.
            for (size_t i = pf.size(); i-- > first_conn;) {
                if (!pf[i].revents)
                    continue;
                size_t idx = i - first_conn;
                if (!on_readable(conns_[idx]))
                    close_conn(idx);
            }
            for (size_t i = 0; i < handlers_.size(); i++)
                if (pf[2 + i].revents)
                    handlers_[i]->on_readable();
            if (pf[1].revents & POLLIN)
                accept_client();
            spin_until = wall_ns() + opt_.spin_us * 1000ull;
        }
        if (stopping_) {
            if (opt_.log)
                std::fprintf(stderr, "vboard: signal during a request, exiting\n");
            return 0;
        }
        if (!lockstep_)
            freerun_step(opt_.freerun_budget_ns);
    }
}

std::unique_ptr<Board> make_board(const std::string &board, std::string &err)
{
    std::string known;
    for (size_t i = 0; i < kNumBoardFactories; i++) {
        if (auto b = kBoardFactories[i]->make(board))
            return b;
        for (const std::string &n : kBoardFactories[i]->boards())
            known += (known.empty() ? "" : ", ") + n;
    }
    err = "unknown board '" + board + "' (this vboard knows: " + (known.empty() ? "none" : known) +
          ")";
    return nullptr;
}

} // namespace vb
