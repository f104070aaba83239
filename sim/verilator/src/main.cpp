// SPDX-License-Identifier: GPL-2.0-or-later
//
// vboard - a virtual FPGA board on a Unix-domain socket (docs/vboard.md).
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <getopt.h>
#include <pthread.h>
#include <sstream>
#include <string>
#include <sys/signalfd.h>
#include <unistd.h>
#include <vector>

#include "board.h"
#include "../eth/eth_board.h"
#include "../eth/udp.h"
#include "plant/machine.h"
#include "sserial/remotes.h"
#include "server.h"
#include "vcd2fst.h"

namespace {

struct Options {
    vb::ServerOptions server;
    std::string board, firmware, dump, machine;
    std::string model = "auto"; // --model rtl|fast|auto
    std::string flash, flash_part;
    uint32_t flash_speedup = 1;
    std::string udp;
    uint32_t udp_tick_us = 0; // --udp-tick: board time per servo datagram (0 = free-running)
    bool udp_rt = false;      // --udp-rt: serve LBP16 at real-time priority
    std::vector<vb_loop> loops;
    std::vector<vb_quad> quads;
    std::vector<vb::sserial::RemoteSpec> remotes;
    bool list = false;
};

void usage(FILE *f)
{
    std::fprintf(f,
                 "usage: vboard --socket PATH --board NAME [--firmware NAME] [--freerun]\n"
                 "              [--loop FROM:TO[:inv]]... [--loop-file FILE]\n"
                 "              [--quad A:B:RATE | A:B:I:RATE[:EVERY]]... [--dump FILE.vcd|.fst] [--log]\n"
                 "              [--spin USEC] [--socket-mode OCTAL] [--machine FILE] [--sserial P.C=TYPE]...\n"
                 "              [--flash FILE] [--flash-part m25p16] [--flash-speedup N]\n"
                 "              [--model rtl|fast|auto]\n"
                 "       vboard --udp ADDR[:PORT] [--udp-tick USEC | --udp-rt] [--socket PATH] --board 7i76e|7i92|7i96s\n"
                 "              [--firmware NAME] [--flash FILE] ...\n"
                 "       vboard --list\n"
                 "A virtual FPGA board running Verilated firmware; see docs/vboard.md.\n");
}

bool parse_u32(const std::string &s, uint32_t &v)
{
    if (s.empty())
        return false;
    char *end = nullptr;
    errno = 0;
    unsigned long x = std::strtoul(s.c_str(), &end, 0);
    if (errno || *end || x > UINT32_MAX || s[0] == '-')
        return false;
    v = static_cast<uint32_t>(x);
    return true;
}

std::vector<std::string> split(const std::string &s, char sep)
{
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, sep))
        out.push_back(item);
    if (!s.empty() && s.back() == sep)
        out.push_back("");
    return out;
}

// FROM:TO[:inv]
bool parse_loop(const std::string &spec, vb_loop &l, std::string &err)
{
    std::vector<std::string> f = split(spec, ':');
    l = vb_loop{};
    if (f.size() < 2 || f.size() > 3 || !parse_u32(f[0], l.from) || !parse_u32(f[1], l.to) ||
        (f.size() == 3 && f[2] != "inv")) {
        err = "bad loop '" + spec + "': want FROM:TO or FROM:TO:inv (I/O pin numbers)";
        return false;
    }
    l.invert = f.size() == 3;
    return true;
}

// A:B:RATE or A:B:I:RATE[:EVERY]
bool parse_quad(const std::string &spec, vb_quad &q, std::string &err)
{
    std::vector<std::string> f = split(spec, ':');
    q = vb_quad{};
    q.pin_index = UINT32_MAX;
    bool ok = f.size() >= 3 && f.size() <= 5 && parse_u32(f[0], q.pin_a) && parse_u32(f[1], q.pin_b);
    std::string rate;
    if (ok && f.size() == 3) {
        rate = f[2];
    } else if (ok) {
        ok = parse_u32(f[2], q.pin_index);
        rate = f[3];
        q.index_every = 100;
        if (ok && f.size() == 5)
            ok = parse_u32(f[4], q.index_every);
    }
    char *end = nullptr;
    if (ok) {
        q.counts_per_s = std::strtod(rate.c_str(), &end);
        ok = !rate.empty() && *end == '\0';
    }
    if (!ok)
        err = "bad quadrature source '" + spec +
              "': want A:B:RATE or A:B:INDEX:RATE[:EVERY] (pins, counts/s, counts per index)";
    return ok;
}

bool read_loop_file(const std::string &path, std::vector<vb_loop> &loops, std::string &err)
{
    std::ifstream in(path);
    if (!in) {
        err = "cannot read loop file " + path + ": " + std::strerror(errno);
        return false;
    }
    std::string line;
    for (int no = 1; std::getline(in, line); no++) {
        size_t hash = line.find('#');
        if (hash != std::string::npos)
            line.erase(hash);
        std::stringstream ss(line);
        std::string word;
        while (ss >> word) {
            vb_loop l;
            if (!parse_loop(word, l, err)) {
                err = path + ":" + std::to_string(no) + ": " + err;
                return false;
            }
            loops.push_back(l);
        }
    }
    return true;
}

int parse_args(int argc, char **argv, Options &o)
{
    static const option longopts[] = {
        {"socket", required_argument, nullptr, 's'},  {"board", required_argument, nullptr, 'b'},
        {"firmware", required_argument, nullptr, 'f'}, {"freerun", no_argument, nullptr, 'r'},
        {"loop", required_argument, nullptr, 'l'},    {"loop-file", required_argument, nullptr, 'L'},
        {"quad", required_argument, nullptr, 'q'},    {"dump", required_argument, nullptr, 'd'},
        {"log", no_argument, nullptr, 'g'},           {"list", no_argument, nullptr, 'i'},
        {"help", no_argument, nullptr, 'h'},          {"spin", required_argument, nullptr, 'p'},
        {"socket-mode", required_argument, nullptr, 'm'}, {"machine", required_argument, nullptr, 'M'},
        {"flash", required_argument, nullptr, 'F'},   {"flash-part", required_argument, nullptr, 'P'},
        {"flash-speedup", required_argument, nullptr, 'S'},
        {"udp", required_argument, nullptr, 'U'},     {"udp-tick", required_argument, nullptr, 'T'},
        {"sserial", required_argument, nullptr, 'R'}, {"udp-rt", no_argument, nullptr, 'Y'},
        {"model", required_argument, nullptr, 'O'},
        {nullptr, 0, nullptr, 0}};
    std::string err;
    int c;
    while ((c = getopt_long(argc, argv, "s:b:f:", longopts, nullptr)) != -1) {
        vb_loop l;
        vb_quad q;
        switch (c) {
        case 's': o.server.socket_path = optarg; break;
        case 'b': o.board = optarg; break;
        case 'f': o.firmware = optarg; break;
        case 'r': o.server.freerun = true; break;
        case 'g': o.server.log = true; break;
        case 'i': o.list = true; break;
        case 'd': o.dump = optarg; break;
        case 'M': o.machine = optarg; break;
        case 'R': {
            vb::sserial::RemoteSpec r;
            if (!vb::sserial::parse_remote(optarg, r, err))
                goto bad;
            o.remotes.push_back(r);
            break;
        }
        case 'O':
            o.model = optarg;
            if (o.model != "rtl" && o.model != "fast" && o.model != "auto") {
                err = std::string("bad --model '") + optarg + "': want rtl, fast or auto";
                goto bad;
            }
            break;
        case 'F': o.flash = optarg; break;
        case 'P': o.flash_part = optarg; break;
        case 'S':
            if (!parse_u32(optarg, o.flash_speedup) || o.flash_speedup == 0 ||
                o.flash_speedup > 1000000) {
                err = std::string("bad --flash-speedup '") + optarg + "': want 1..1000000";
                goto bad;
            }
            break;
        case 'U': o.udp = optarg; break;
        case 'Y': o.udp_rt = true; break;
        case 'm': {
            char *end = nullptr;
            errno = 0;
            unsigned long m = std::strtoul(optarg, &end, 8);
            if (errno || !*optarg || *end || m > 0777 || (m & 0600) != 0600) {
                err = std::string("bad --socket-mode '") + optarg +
                      "': want octal permission bits that include 0600 (e.g. 0660)";
                goto bad;
            }
            o.server.socket_mode = static_cast<unsigned>(m);
            break;
        }
        case 'T':
            if (!parse_u32(optarg, o.udp_tick_us) || o.udp_tick_us == 0 ||
                o.udp_tick_us > 1000000) {
                err = std::string("bad --udp-tick '") + optarg + "': want microseconds, 1..1000000";
                goto bad;
            }
            break;
        case 'p': {
            uint32_t us;
            if (!parse_u32(optarg, us) || us > 1000000) {
                err = std::string("bad --spin '") + optarg + "': want microseconds, 0..1000000";
                goto bad;
            }
            o.server.spin_us = us;
            break;
        }
        case 'l':
            if (!parse_loop(optarg, l, err))
                goto bad;
            o.loops.push_back(l);
            break;
        case 'L':
            if (!read_loop_file(optarg, o.loops, err))
                goto bad;
            break;
        case 'q':
            if (!parse_quad(optarg, q, err))
                goto bad;
            o.quads.push_back(q);
            break;
        case 'h': usage(stdout); return 0;
        default: usage(stderr); return 2;
        }
    }
    if (optind < argc) {
        err = std::string("unexpected argument '") + argv[optind] + "'";
        goto bad;
    }
    if (o.udp_tick_us && o.udp.empty()) {
        err = "--udp-tick needs --udp";
        goto bad;
    }
    if (o.udp_rt && (o.udp.empty() || o.udp_tick_us)) {
        err = "--udp-rt needs --udp and a free-running board (no --udp-tick: a tick would run "
              "the simulation at real-time priority)";
        goto bad;
    }
    if (!o.list && ((o.server.socket_path.empty() && o.udp.empty()) || o.board.empty())) {
        err = "--socket and --board are required (an Ethernet board may take --udp instead of "
              "--socket)";
        goto bad;
    }
    return -1;
bad:
    std::fprintf(stderr, "vboard: %s\n", err.c_str());
    usage(stderr);
    return 2;
}

int list_boards()
{
    std::vector<std::string> seen; // a board two families know is listed once
    for (size_t i = 0; i < vb::kNumBoardFactories; i++)
        for (const std::string &name : vb::kBoardFactories[i]->boards()) {
            if (std::find(seen.begin(), seen.end(), name) != seen.end())
                continue;
            seen.push_back(name);
            auto b = vb::kBoardFactories[i]->make(name);
            std::printf("%s (%s):", name.c_str(), b ? b->fpga_part().c_str() : "?");
            if (b)
                for (const std::string &fw : b->firmwares())
                    std::printf(" %s", fw.c_str());
            std::printf("\n");
        }
    return 0;
}

// Command-line wiring, applied like the equivalent requests.
int setup(vb::Board &b, const Options &o)
{
    std::string err;
    // A waveform dump needs the RTL model: --dump makes auto mean rtl.
    if (b.set_model(o.model == "auto" && !o.dump.empty() ? "rtl" : o.model, o.firmware, err) < 0)
        goto bad;
    if (b.flash_configured() || !o.flash.empty() || !o.flash_part.empty()) {
        // Flash-configured boards boot from their flash; --firmware is what
        // a new flash is factory-programmed with.
        if (b.attach_flash(o.flash, o.flash_part, o.flash_speedup, o.firmware, err) < 0)
            goto bad;
    } else if (!o.firmware.empty() && b.load(o.firmware, err) < 0) {
        goto bad;
    }
    for (const vb_loop &l : o.loops)
        if (b.pins().loop(l.from, l.to, l.invert != 0, b.now_ns(), err) < 0)
            goto bad;
    for (const vb_quad &q : o.quads)
        if (b.pins().quad(q, b.now_ns(), err) < 0)
            goto bad;
    if (!o.dump.empty()) {
        if (o.dump.size() >= 4 && o.dump.compare(o.dump.size() - 4, 4, ".fst") == 0 &&
            !vb::have_fst()) {
            err = "dump " + o.dump +
                  ": this vboard was built without FST support (liblz4-dev missing); use .vcd";
            goto bad;
        }
        if (b.dump(true, o.dump, err) < 0)
            goto bad;
    }
    return 0;
bad:
    std::fprintf(stderr, "vboard: %s\n", err.c_str());
    return 1;
}

// The firmware whose pin map places the Smart Serial channels: --firmware,
// else the only firmware of this board that has Smart Serial pins.
std::string sserial_firmware(const vb::Board &b, const Options &o, std::string &err)
{
    if (!o.firmware.empty())
        return o.firmware;
    if (b.configured())
        return b.firmware();
    std::string found;
    for (const std::string &fw : b.firmwares())
        for (const auto &pn : b.pin_names(fw))
            if (pn.second.rfind("SSerial ", 0) == 0) {
                if (!found.empty() && found != fw) {
                    err = "--sserial: board " + b.name() + " has several firmwares with Smart "
                          "Serial (" + found + ", " + fw + "): name one with --firmware";
                    return "";
                }
                found = fw;
                break;
            }
    if (found.empty())
        err = "--sserial: no firmware of board " + b.name() + " has a Smart Serial port";
    return found;
}

int attach_remotes(vb::Board &b, const Options &o, std::unique_ptr<vb::sserial::Remotes> &out)
{
    std::string err;
    std::string fw = sserial_firmware(b, o, err);
    auto r = std::make_unique<vb::sserial::Remotes>();
    uint32_t clock_low = 0;
    if (!fw.empty()) {
        clock_low = b.configured() && b.firmware() == fw ? b.clock_low_hz() : 0;
        if (!clock_low)
            clock_low = b.firmware_clock_low_hz(fw);
    }
    if (fw.empty() || !clock_low ||
        !r->configure(o.remotes, fw, b.pin_names(fw), clock_low, err)) {
        if (err.empty())
            err = "--sserial: unknown ClockLow of firmware " + fw;
        std::fprintf(stderr, "vboard: %s\n", err.c_str());
        return 1;
    }
    r->attach(b.pins(), b.now_ns());
    out = std::move(r);
    return 0;
}

} // namespace

int main(int argc, char **argv)
{
    // SIGTERM/SIGINT arrive through a signalfd, so the poll loop handles
    // them like any other event and the destructors clean up (socket file).
    // Blocked first thing, before any thread exists (threads inherit it).
    sigset_t mask;
    sigemptyset(&mask);
    sigaddset(&mask, SIGTERM);
    sigaddset(&mask, SIGINT);
    pthread_sigmask(SIG_BLOCK, &mask, nullptr);
    std::signal(SIGPIPE, SIG_IGN);

    Options o;
    int rc = parse_args(argc, argv, o);
    if (rc >= 0)
        return rc;
    if (o.list)
        return list_boards();

    std::string err;
    std::unique_ptr<vb::Board> board = vb::make_board(o.board, err);
    if (!board) {
        std::fprintf(stderr, "vboard: %s\n", err.c_str());
        return 1;
    }
    auto *eth = dynamic_cast<vb::eth::EthBoard *>(board.get());
    uint32_t udp_ip = 0;
    uint16_t udp_port = 0;
    if (!o.udp.empty()) {
        if (!eth) {
            std::fprintf(stderr, "vboard: --udp is for Ethernet boards (%s is not one)\n",
                         o.board.c_str());
            return 1;
        }
        if (!vb::eth::parse_udp_addr(o.udp, udp_ip, udp_port, err)) {
            std::fprintf(stderr, "vboard: %s\n", err.c_str());
            return 2;
        }
        // An Ethernet board runs on its own clock: datagrams carry no time.
        // With --udp-tick the board runs only when a datagram asks it to.
        if (!o.udp_tick_us) {
            o.server.freerun = true;
            o.server.freerun_slice_ns = 1000;
            o.server.freerun_budget_ns = 100000;
        }
        eth->set_ip(udp_ip);
    }
    if (setup(*board, o) != 0)
        return 1;
    std::unique_ptr<vb::plant::Machine> machine;
    if (!o.machine.empty()) {
        vb::plant::MachineSpec spec;
        vb::Board &b = *board;
        auto names = [&b](const std::string &fw) { return b.pin_names(fw); };
        if (!vb::plant::load_machine(o.machine, o.board, names, b.pins().size(), spec, err)) {
            std::fprintf(stderr, "vboard: %s\n", err.c_str());
            return 1;
        }
        machine = std::make_unique<vb::plant::Machine>(spec);
        machine->attach(b.pins(), b.now_ns());
    }

    std::unique_ptr<vb::sserial::Remotes> remotes;
    if (!o.remotes.empty() && attach_remotes(*board, o, remotes) != 0)
        return 1;

    int sfd = signalfd(-1, &mask, SFD_CLOEXEC);
    if (sfd < 0) {
        std::fprintf(stderr, "vboard: signalfd: %s\n", std::strerror(errno));
        return 1;
    }
    int status;
    {
        vb::Server server(*board, o.server);
        server.set_plant(machine.get());
        server.set_sserial(remotes.get());
        std::unique_ptr<vb::eth::UdpEndpoint> udp;
        if (!o.udp.empty()) {
            udp = std::make_unique<vb::eth::UdpEndpoint>(*eth, o.server.log);
            udp->set_tick_ns(o.udp_tick_us * 1000ull);
        }
        if ((!o.server.socket_path.empty() && server.open(err) < 0) ||
            (udp && udp->open(udp_ip, udp_port, err) < 0) ||
            (o.udp_rt && vb::eth::serve_at_rt_priority(err) < 0)) {
            std::fprintf(stderr, "vboard: %s\n", err.c_str());
            ::close(sfd);
            return 1;
        }
        if (udp)
            server.add_handler(udp.get());
        std::string fw = board->firmware();
        std::string where = o.server.socket_path;
        if (!o.udp.empty()) {
            char b[64];
            std::snprintf(b, sizeof b, "udp %u.%u.%u.%u:%u", udp_ip >> 24, (udp_ip >> 16) & 255,
                          (udp_ip >> 8) & 255, udp_ip & 255, udp->port());
            where += (where.empty() ? "" : " and ") + std::string(b);
        }
        std::printf("vboard: ready on %s (%s, %s)\n", where.c_str(), board->name().c_str(),
                    fw.empty() ? "blank" : fw.c_str());
        std::fflush(stdout);
        status = server.run(sfd);
    }
    board->pins().set_agent(nullptr);
    std::string derr;
    board->dump(false, "", derr);
    ::close(sfd);
    return status;
}
