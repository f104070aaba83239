// SPDX-License-Identifier: GPL-2.0-or-later
// epp_fpga_board.cpp - see epp_fpga_board.h.
#include "epp_fpga_board.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "fwimage.h"

namespace vb {

std::vector<std::string> EppFpgaBoard::firmwares() const
{
    std::vector<std::string> v;
    for (int i = 0; i < fw_count(); i++)
        v.push_back(fw_name(i));
    return v;
}

void EppFpgaBoard::run_until(uint64_t t)
{
    if (!model_) {
        if (t > now_) {
            pins_.run_events(t);
            now_ = t;
        }
        return;
    }
    while (model_ && now_ + th_ <= t)
        step();
    if (!model_ && t > now_)
        run_until(t); // the firmware went away (reconfiguration)
}

int EppFpgaBoard::config(uint32_t op, const uint8_t *, size_t, vb_config_status &st,
                         std::string &err)
{
    std::memset(&st, 0, sizeof st);
    st.done = model_ ? 1 : 0;
    st.init = 1;
    std::strncpy(st.firmware, firmware().c_str(), sizeof st.firmware - 1);
    if (op == VB_CONFIG_STATUS)
        return 0;
    err = std::string(board_) + ": " + how_ + ", not through the configuration port";
    return -ENOTSUP;
}

int EppFpgaBoard::load(const std::string &firmware, std::string &err)
{
    for (int i = 0; i < fw_count(); i++)
        if (firmware == fw_name(i)) {
            start(i);
            return 0;
        }
    err = "firmware " + firmware + " is not built into this vboard for board " + board_ +
          " (built:";
    for (int i = 0; i < fw_count(); i++)
        err += std::string(i ? ", " : " ") + fw_name(i);
    err += ")";
    return -ENOENT;
}

void EppFpgaBoard::step()
{
    uint64_t t = now_ + th_;
    if (pins_.next_event_ns() <= t)
        pins_.run_events(t);
    const uint32_t *lv = pins_.inputs();
    EppFpgaIn in;
    in.d = bus_.d;
    in.nwrite = bus_.nwrite;
    in.ndatastr = bus_.ndatastr;
    in.naddrstr = bus_.naddrstr;
    in.nreset = (control_ & 0x04) != 0; // nInit
    in.io_in = fpga_inputs(lv[0] | (static_cast<uint64_t>(lv[1]) << 32));
    if (pins_.words() > 2)
        in.io_in_hi = lv[2];
    model_->clock(in, out_);
    uint64_t o = out_.io_out & fpga_output_mask(), e = out_.io_oe & fpga_output_mask();
    uint32_t ow[3] = {static_cast<uint32_t>(o), static_cast<uint32_t>(o >> 32), out_.io_out_hi};
    uint32_t ew[3] = {static_cast<uint32_t>(e), static_cast<uint32_t>(e >> 32), out_.io_oe_hi};
    pins_.set_fpga(ow, ew, t);
    now_ = t;
    stepped();
}

void EppFpgaBoard::start(int i)
{
    fw_ = i;
    model_ = make_model(i, th_);
    out_ = EppFpgaOut{};
}

void EppFpgaBoard::unconfigure()
{
    model_.reset();
    fw_ = -1;
    pins_.release_fpga(now_);
}

void EppFpgaBoard::configure_from(const std::vector<uint8_t> &image)
{
    std::string err;
    std::vector<BuiltFw> built;
    for (int i = 0; i < fw_count(); i++)
        built.push_back({fw_name(i), fw_build_id(i)});
    int i = match_fw_image(image.data(), image.size(), board_, built, id_label_, err);
    if (i >= 0) {
        std::fprintf(stderr, "vboard: %s: configured with %s\n", board_, fw_name(i));
        start(i);
        return;
    }
    std::fprintf(stderr, "vboard: %s: configuration failed, board stays blank: %s\n", board_,
                 err.c_str());
}

} // namespace vb
