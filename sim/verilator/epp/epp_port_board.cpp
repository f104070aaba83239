// SPDX-License-Identifier: GPL-2.0-or-later
// epp_port_board.cpp - see epp_port_board.h.
#include "epp_port_board.h"

#include <cerrno>
#include <cstring>

namespace vb {

namespace {
constexpr uint8_t kStatusTimeout = 0x01;
constexpr uint64_t kCpldCycleNs = 250;
// enum epp_op_kind (host/driver/include/hm2/epp_port.h)
// One request may ask for at most this many EPP cycles (~1 s of bus time,
// more than a whole FPGA bitstream) and this much waiting: a request must
// not keep the board simulating for minutes while other clients wait.
constexpr uint64_t kMaxCyclesPerRequest = 1u << 20;
constexpr uint64_t kMaxDelayPerRequestNs = 1000000000u;
enum : uint8_t {
    OP_ADDR_WRITE = 1, OP_ADDR_READ, OP_DATA_WRITE, OP_DATA_READ, OP_STATUS_READ,
    OP_STATUS_WRITE, OP_CONTROL_WRITE, OP_SPP_DATA_WRITE, OP_ECR_WRITE, OP_DELAY
};
} // namespace

void EppPortBoard::wait_ns(uint64_t ns)
{
    uint64_t end = now_ + ns;
    if (!fpga_running()) {
        run_until(end);
        return;
    }
    while (now_ < end && fpga_running())
        step();
    if (now_ < end)
        run_until(end); // the firmware went away (reconfiguration)
}

bool EppPortBoard::cycle(bool addr, bool write, uint8_t w, uint8_t &r)
{
    r = 0xFF;
    if (status_ & kStatusTimeout)
        return false; // the port refuses cycles until the bit is cleared
    if (!fpga_running()) {
        bool ok = !stall_ && blank_cycle(addr, write, w, r);
        wait_ns(ok ? kCpldCycleNs : kEppTimeoutNs);
        if (!ok) {
            r = 0xFF;
            status_ |= kStatusTimeout;
        }
        return ok;
    }
    bus_.nwrite = !write;
    bus_.d = write ? w : 0xFF;
    wait_ns(step_ns()); // setup
    (addr ? bus_.naddrstr : bus_.ndatastr) = false;
    uint64_t start = now_;
    bool ok = true;
    while (!ack()) {
        if (!fpga_running())
            break; // the write reconfigured the FPGA (7i43 RECONFIG): it got in
        if (now_ - start >= kEppTimeoutNs) {
            ok = false;
            break;
        }
        wait_ns(step_ns());
    }
    if (ok && !write && !fpga_data(r))
        r = 0xFF;
    (addr ? bus_.naddrstr : bus_.ndatastr) = true;
    if (ok) {
        start = now_;
        while (ack() && now_ - start < kEppTimeoutNs)
            wait_ns(step_ns());
        ok = !ack();
    }
    bus_.nwrite = true;
    bus_.d = 0xFF;
    wait_ns(step_ns()); // recovery
    if (!ok)
        status_ |= kStatusTimeout;
    return ok;
}

void EppPortBoard::execute(const vb_epp_op &op, const uint8_t *data, std::vector<uint8_t> &out)
{
    uint8_t b = 0;
    switch (op.kind) {
    case OP_ADDR_WRITE:
        cycle(true, true, static_cast<uint8_t>(op.val), b);
        break;
    case OP_ADDR_READ:
        cycle(true, false, 0, b);
        out.push_back(b);
        break;
    case OP_DATA_WRITE:
        for (uint32_t i = 0; i < op.n; i++)
            cycle(false, true, data[i], b);
        break;
    case OP_DATA_READ:
        for (uint32_t i = 0; i < op.n; i++) {
            cycle(false, false, 0, b);
            out.push_back(b);
        }
        break;
    case OP_STATUS_READ:
        out.push_back(status_);
        break;
    case OP_STATUS_WRITE:
        // Ports differ (clear on writing 1 or on 0); the drivers write
        // both, this one clears on a 1.
        if (op.val & kStatusTimeout)
            status_ &= static_cast<uint8_t>(~kStatusTimeout);
        break;
    case OP_CONTROL_WRITE: {
        uint8_t old = control_;
        control_ = static_cast<uint8_t>(op.val);
        control_written(old, control_);
        break;
    }
    case OP_SPP_DATA_WRITE:
        spp_ = static_cast<uint8_t>(op.val);
        break;
    case OP_ECR_WRITE:
        ecr_ = static_cast<uint8_t>(op.val);
        break;
    case OP_DELAY:
        wait_ns(op.val);
        break;
    default:
        break;
    }
}

int EppPortBoard::epp(const uint8_t *req, size_t len, std::vector<uint8_t> &out, std::string &err)
{
    // Parse everything first: a payload that does not parse changes nothing.
    size_t off = 0, nreads = 0;
    uint64_t cycles = 0, delay_ns = 0;
    while (off < len) {
        vb_epp_op op;
        if (len - off < sizeof op) {
            err = "EPP request: truncated operation at byte " + std::to_string(off);
            return -EPROTO;
        }
        std::memcpy(&op, req + off, sizeof op);
        off += sizeof op;
        if (op.kind < OP_ADDR_WRITE || op.kind > OP_DELAY) {
            err = "EPP request: unknown operation kind " + std::to_string(op.kind) + " at byte " +
                  std::to_string(off - sizeof op);
            return -EPROTO;
        }
        if (op.kind == OP_DATA_WRITE) {
            if (len - off < op.n) {
                err = "EPP request: data write of " + std::to_string(op.n) +
                      " bytes runs past the payload";
                return -EPROTO;
            }
            off += op.n;
        }
        nreads += op.kind == OP_DATA_READ ? op.n
                  : (op.kind == OP_ADDR_READ || op.kind == OP_STATUS_READ) ? 1 : 0;
        if (nreads > VB_MAX_PAYLOAD) {
            err = "EPP request: reads more than the reply can carry";
            return -EPROTO;
        }
        cycles += op.kind == OP_DATA_READ || op.kind == OP_DATA_WRITE ? op.n
                  : (op.kind == OP_ADDR_READ || op.kind == OP_ADDR_WRITE) ? 1 : 0;
        delay_ns += op.kind == OP_DELAY ? op.val : 0;
        if (cycles > kMaxCyclesPerRequest) {
            err = "EPP request: more than " + std::to_string(kMaxCyclesPerRequest) +
                  " bus cycles in one request";
            return -E2BIG;
        }
        if (delay_ns > kMaxDelayPerRequestNs) {
            err = "EPP request: delays add up to more than 1 s in one request";
            return -E2BIG;
        }
    }
    out.reserve(out.size() + nreads);
    for (off = 0; off < len;) {
        vb_epp_op op;
        std::memcpy(&op, req + off, sizeof op);
        off += sizeof op;
        execute(op, req + off, out);
        if (op.kind == OP_DATA_WRITE)
            off += op.n;
    }
    return 0;
}

int EppPortBoard::epp_stall(bool on, std::string &)
{
    stall_ = on;
    return 0;
}

} // namespace vb
