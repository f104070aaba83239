// SPDX-License-Identifier: GPL-2.0-or-later
//
// libFuzzer target: the virtual board's socket protocol, server side
// (sim/verilator/src/server.cpp: framing, request dispatch and payload
// checks of every request type) with the EPP port model behind it
// (sim/verilator/epp/epp_port_board.cpp: EPP operation lists, the
// pin-level cycle engine and its timeout) and the firmware image check.
// The board's firmware is a small stand-in (an echo register) so a run
// costs microseconds; the Verilated firmwares are covered by the e2e tests.
//
// The input is a byte stream as a client would send it.  Replies are
// drained from the other end of a socket pair by a second thread.
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "epp_port_board.h"
#include "fwimage.h"
#include "server.h"
#include "vcd2fst.h"

namespace vb {
// The FST converter is not linked (the stand-in board cannot dump).
bool have_fst()
{
    return false;
}
int vcd_to_fst(const std::string &, const std::string &, std::string &err)
{
    err = "no FST support in the fuzz target";
    return -ENOTSUP;
}
// No board factories: the target makes its board itself.
const BoardFactory *const kBoardFactories[] = {nullptr};
const size_t kNumBoardFactories = 0;
} // namespace vb

namespace {

class EchoBoard : public vb::EppPortBoard {
  public:
    EchoBoard() : pins_(16) {}
    std::string name() const override { return "pluto"; }
    std::string fpga_part() const override { return "ep1k10tc100"; }
    uint32_t bus() const override { return VB_BUS_EPP_PLUTO; }
    std::string firmware() const override { return fw_; }
    uint32_t clock_low_hz() const override { return fw_.empty() ? 0 : 40000000; }
    uint32_t clock_high_hz() const override { return 0; }
    std::vector<std::string> firmwares() const override { return {"echo"}; }
    vb::PinBank &pins() override { return pins_; }
    void run_until(uint64_t t) override
    {
        if (t > now_)
            now_ = t;
    }
    int config(uint32_t op, const uint8_t *bits, size_t len, vb_config_status &st,
               std::string &err) override
    {
        int r = 0;
        if (op == VB_CONFIG_RESET) {
            fw_.clear();
        } else if (op == VB_CONFIG_PROGRAM) {
            vb::FwImage img;
            fw_.clear();
            r = vb::parse_fw_image(bits, len, img, err);
            if (r == 0)
                fw_ = "echo";
        } else if (op != VB_CONFIG_STATUS) {
            err = "unknown configuration operation";
            r = -EINVAL;
        }
        std::memset(&st, 0, sizeof st);
        st.done = fw_.empty() ? 0 : 1;
        st.init = 1;
        std::memcpy(st.firmware, fw_.c_str(), fw_.size() + 1);
        return r;
    }
    int load(const std::string &firmware, std::string &err) override
    {
        if (firmware != "echo") {
            err = "no firmware " + firmware;
            return -ENOENT;
        }
        fw_ = firmware;
        return 0;
    }

  protected:
    bool fpga_running() const override { return !fw_.empty(); }
    void step() override
    {
        // acknowledge a strobe one clock later; a write strobe latches data
        bool strobe = !bus_.ndatastr || !bus_.naddrstr;
        if (strobe && !bus_.nwrite)
            reg_ = bus_.d;
        ack_ = strobe;
        now_ += step_ns();
    }
    uint64_t step_ns() const override { return 500; }
    bool fpga_nwait() const override { return ack_; }
    bool fpga_data(uint8_t &d) const override
    {
        d = reg_;
        return true;
    }

  private:
    vb::PinBank pins_;
    std::string fw_;
    uint8_t reg_ = 0;
    bool ack_ = false;
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    int sv[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
        std::abort();
    std::thread drain([fd = sv[1]] {
        char buf[65536];
        while (::read(fd, buf, sizeof buf) > 0) {
        }
    });
    {
        EchoBoard board;
        vb::ServerOptions opt;
        opt.socket_path = "(fuzz)";
        vb::Server server(board, opt);
        server.serve_bytes(sv[0], data, size);
    }
    ::shutdown(sv[0], SHUT_RDWR);
    ::close(sv[0]);
    drain.join();
    ::close(sv[1]);
    return 0;
}
