// SPDX-License-Identifier: GPL-2.0-or-later
//
// vbi.cpp - the virtual local-bus board as a library (vboard/inproc.h):
// the vboard program's LocalBusBoard, its time rule and its request checks,
// behind a C table of functions for the hm2_sim module's in-process llio.
#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <system_error>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <vector>

#include "localbus.h"
#include "vboard/inproc.h"

namespace {

constexpr uint32_t kLbWindow = 0x10000;                  // the hm2 address space
constexpr uint64_t kMaxAdvanceNs = 60ull * 1000000000ull; // as the socket server
constexpr uint64_t kFreerunSliceNs = 10000;   // board time per step of the board thread
constexpr uint64_t kFreerunMaxLagNs = 50000000; // behind by more: re-base (as the server)

uint64_t mono_ns()
{
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<uint64_t>(ts.tv_sec) * 1000000000ull + static_cast<uint64_t>(ts.tv_nsec);
}

} // namespace

struct vbi_board {
    std::unique_ptr<vb::Board> b;
    std::string err;
    // Serializes the board between API calls and the free-running thread;
    // `want` makes that thread step aside when a call waits.
    std::mutex mu;
    std::atomic<int> want{0};
    std::thread runner;
    std::atomic<bool> running{false};
    uint64_t fr_wall0 = 0, fr_board0 = 0;
    bool have_epoch = false;
    int64_t epoch = 0;
    vbi_stats st{};
    std::vector<uint8_t> buf; // read data / gathered write data, reused
    std::vector<vb_pin> pins;

    int fail(int rc, const std::string &msg)
    {
        err = "virtual board " + b->name() + " (in-process): " + msg;
        return rc;
    }

    // The socket server's lockstep rule (Server::advance_lockstep).
    int advance(uint64_t host_time)
    {
        if (host_time == 0 || running)
            return 0;
        if (!have_epoch) {
            epoch = static_cast<int64_t>(host_time - b->now_ns());
            have_epoch = true;
            return 0;
        }
        int64_t target = static_cast<int64_t>(host_time - static_cast<uint64_t>(epoch));
        if (target <= 0 || static_cast<uint64_t>(target) <= b->now_ns())
            return 0;
        uint64_t jump = static_cast<uint64_t>(target) - b->now_ns();
        if (jump > kMaxAdvanceNs) {
            have_epoch = false;
            char m[200];
            std::snprintf(m, sizeof m,
                          "the host time jump of %.3f s is more than one call may advance the "
                          "board (%.0f s); the board's time is unchanged; the next call re-takes "
                          "the epoch",
                          static_cast<double>(jump) * 1e-9,
                          static_cast<double>(kMaxAdvanceNs) * 1e-9);
            return fail(-ERANGE, m);
        }
        b->run_until(static_cast<uint64_t>(target));
        return 0;
    }

    int check(const vb_xfer *x, size_t n, const char *what)
    {
        for (size_t i = 0; i < n; i++) {
            char m[160];
            if (x[i].addr % 4 || x[i].size % 4) {
                std::snprintf(m, sizeof m,
                              "%s of %u bytes at 0x%x: address and size must be multiples of 4",
                              what, x[i].size, x[i].addr);
                return fail(-EINVAL, m);
            }
            if (x[i].addr >= kLbWindow || x[i].size > kLbWindow - x[i].addr) {
                std::snprintf(m, sizeof m, "%s of %u bytes at 0x%x runs outside the 64 KiB hm2 "
                              "window", what, x[i].size, x[i].addr);
                return fail(-EINVAL, m);
            }
        }
        return 0;
    }
};

namespace {

// Holds the board for an API call: the free-running thread steps aside.
class Hold {
  public:
    explicit Hold(vbi_board *v) : v_(v)
    {
        v_->want++;
        v_->mu.lock();
        v_->want--;
    }
    ~Hold() { v_->mu.unlock(); }
    Hold(const Hold &) = delete;
    Hold &operator=(const Hold &) = delete;

  private:
    vbi_board *v_;
};

// The board thread of a free-running board (Server::freerun_step's rule).
void run_free(vbi_board *v)
{
    while (v->running) {
        bool idle;
        {
            std::lock_guard<std::mutex> g(v->mu);
            uint64_t now = v->b->now_ns();
            uint64_t target = v->fr_board0 + (mono_ns() - v->fr_wall0);
            if (target > now && target - now > kFreerunMaxLagNs) {
                v->fr_wall0 = mono_ns();
                v->fr_board0 = now;
                target = now + kFreerunSliceNs;
            }
            idle = target <= now;
            if (!idle)
                v->b->run_until(std::min(target, now + kFreerunSliceNs));
        }
        if (idle || v->want > 0) {
            timespec ts{0, idle ? 50000 : 0};
            if (idle)
                nanosleep(&ts, nullptr);
            else
                std::this_thread::yield();
        }
    }
}

void stop_free(vbi_board *v)
{
    if (!v->runner.joinable())
        return;
    v->running = false;
    v->runner.join();
}

// Times the board's own work (clock advance, bus cycles) for vbi_stats.
struct BoardTimer {
    explicit BoardTimer(vbi_board *v) : v_(v), t0_(mono_ns()) { v_->st.calls++; }
    ~BoardTimer() { v_->st.board_ns += mono_ns() - t0_; }
    BoardTimer(const BoardTimer &) = delete;
    BoardTimer &operator=(const BoardTimer &) = delete;
    vbi_board *v_;
    uint64_t t0_;
};

void put_err(char *err, size_t len, const std::string &m)
{
    if (err && len)
        std::snprintf(err, len, "%s", m.c_str());
}

vbi_board_t *vbi_open(const char *board, const char *firmware, char *err, size_t errlen)
{
    std::string name = board ? board : "", fw = firmware ? firmware : "";
    std::vector<std::string> known = vb::localbus_boards();
    if (std::find(known.begin(), known.end(), name) == known.end()) {
        std::string list;
        for (const std::string &k : known)
            list += (list.empty() ? "" : ", ") + k;
        put_err(err, errlen, "no in-process local-bus board '" + name + "' (built: " + list + ")");
        return nullptr;
    }
    try {
        auto v = std::make_unique<vbi_board>();
        v->b = vb::make_localbus_board(name);
        std::string e;
        int rc = 0;
        // As vboard's command line: flash-configured boards boot from an
        // in-memory flash factory-programmed with the firmware.
        if (v->b->flash_configured())
            rc = v->b->attach_flash("", "", 1, fw, e);
        else if (!fw.empty())
            rc = v->b->load(fw, e);
        if (rc < 0) {
            put_err(err, errlen, "virtual board " + name + " (in-process): " + e);
            return nullptr;
        }
        if (!fw.empty() && v->b->firmware() != fw) {
            put_err(err, errlen, "virtual board " + name + " (in-process): firmware " + fw +
                                     " did not configure the board");
            return nullptr;
        }
        return v.release();
    } catch (const std::bad_alloc &) {
        put_err(err, errlen, "virtual board " + name + " (in-process): out of memory");
        return nullptr;
    }
}

void vbi_close(vbi_board_t *v)
{
    if (!v)
        return;
    stop_free(v);
    std::string e;
    v->b->dump(false, "", e);
    delete v;
}

const char *vbi_error(const vbi_board_t *v) { return v->err.c_str(); }

void vbi_hello(vbi_board_t *v, vb_hello *h)
{
    Hold hold(v);
    std::memset(h, 0, sizeof *h);
    vb::Board &b = *v->b;
    h->version = VB_PROTO_VERSION;
    h->bus = b.bus();
    h->state = b.configured() ? VB_STATE_CONFIGURED : VB_STATE_BLANK;
    h->io_pins = b.pins().size();
    h->clock_low_hz = b.clock_low_hz();
    h->clock_high_hz = b.clock_high_hz();
    h->lockstep = v->running ? 0 : 1;
    std::strncpy(h->board, b.name().c_str(), sizeof h->board - 1);
    std::strncpy(h->firmware, b.firmware().c_str(), sizeof h->firmware - 1);
    std::strncpy(h->fpga_part, b.fpga_part().c_str(), sizeof h->fpga_part - 1);
}

int vbi_read(vbi_board_t *v, uint64_t host_time, const vb_xfer *x, void *const *dest, size_t n)
{
    Hold h(v);
    BoardTimer t(v);
    int rc = v->advance(host_time);
    if (rc < 0 || (rc = v->check(x, n, "read")) < 0)
        return rc;
    v->buf.clear();
    rc = v->b->lb_read(x, n, v->buf, v->err);
    if (rc < 0)
        return v->fail(rc, std::string(v->err));
    const uint8_t *p = v->buf.data();
    for (size_t i = 0; i < n; i++) {
        std::memcpy(dest[i], p, x[i].size);
        p += x[i].size;
        v->st.read_words += x[i].size / 4;
    }
    return 0;
}

int vbi_write(vbi_board_t *v, uint64_t host_time, const vb_xfer *x, const void *const *src,
              size_t n)
{
    Hold h(v);
    BoardTimer t(v);
    int rc = v->advance(host_time);
    if (rc < 0 || (rc = v->check(x, n, "write")) < 0)
        return rc;
    size_t total = 0;
    for (size_t i = 0; i < n; i++)
        total += x[i].size;
    v->buf.resize(total);
    uint8_t *p = v->buf.data();
    for (size_t i = 0; i < n; i++) {
        std::memcpy(p, src[i], x[i].size);
        p += x[i].size;
    }
    rc = v->b->lb_write(x, n, v->buf.data(), v->err);
    if (rc < 0)
        return v->fail(rc, std::string(v->err));
    v->st.write_words += total / 4;
    return 0;
}

int vbi_config(vbi_board_t *v, uint64_t host_time, uint32_t op, const uint8_t *bits, size_t len,
               vb_config_status *st)
{
    Hold h(v);
    BoardTimer t(v);
    int rc = v->advance(host_time);
    if (rc < 0)
        return rc;
    rc = v->b->config(op, bits, len, *st, v->err);
    return rc < 0 ? v->fail(rc, std::string(v->err)) : 0;
}

int vbi_loop(vbi_board_t *v, uint32_t from, uint32_t to, int invert)
{
    Hold h(v);
    int rc = v->b->pins().loop(from, to, invert != 0, v->b->now_ns(), v->err);
    return rc < 0 ? v->fail(rc, std::string(v->err)) : 0;
}

int vbi_probe(vbi_board_t *v, uint32_t first, uint32_t count, vb_pin *out)
{
    Hold h(v);
    v->pins.clear();
    int rc = v->b->pins().probe(first, count, v->b->now_ns(), v->pins, v->err);
    if (rc < 0)
        return v->fail(rc, std::string(v->err));
    std::copy(v->pins.begin(), v->pins.end(), out);
    return 0;
}

uint64_t vbi_now_ns(const vbi_board_t *cv)
{
    auto *v = const_cast<vbi_board_t *>(cv); // the lock, not the board, changes
    Hold h(v);
    return v->b->now_ns();
}

void vbi_stats_get(const vbi_board_t *cv, vbi_stats *out)
{
    auto *v = const_cast<vbi_board_t *>(cv);
    Hold h(v);
    *out = v->st;
}

int vbi_freerun(vbi_board_t *v, int on)
{
    if (!on) {
        stop_free(v);
        Hold h(v);
        v->have_epoch = false; // lockstep again: the next time re-takes the epoch
        return 0;
    }
    if (v->runner.joinable())
        return 0;
    {
        Hold h(v);
        v->fr_wall0 = mono_ns();
        v->fr_board0 = v->b->now_ns();
        v->running = true;
    }
    try {
        v->runner = std::thread(run_free, v);
    } catch (const std::system_error &e) {
        v->running = false;
        return v->fail(-EAGAIN, std::string("cannot start the board thread: ") + e.what());
    }
    return 0;
}

const vbi_api_t kApi = {VBI_ABI,  vbi_open,   vbi_close, vbi_error,  vbi_hello,
                        vbi_read, vbi_write,  vbi_config, vbi_loop,  vbi_probe,
                        vbi_now_ns, vbi_stats_get, vbi_freerun};

} // namespace

extern "C" __attribute__((visibility("default"))) const vbi_api_t *vbi_get_api(void)
{
    return &kApi;
}
