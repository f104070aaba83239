// SPDX-License-Identifier: GPL-2.0-or-later
//
// board.h - what the vboard server needs from a board model.
//
// The server (server.cpp) owns sockets, framing, epochs and free-running
// time; a Board owns the Verilated firmware, its clocks and its pins.  Each
// family of boards (hm2 local-bus boards here, EPP boards in epp/) provides
// a BoardFactory; the build lists the factories (CMake variable
// VBOARD_FACTORIES) in a generated table, so families plug in without the
// server knowing them.
//
// Conventions for every method:
//  * Errors return a negative errno and put a complete message (what failed,
//    on which object, why) into `err`.  Nothing of the request is applied
//    then (the board state stays as it was), except time that has passed.
//  * Time is board time in ns since the board process started; it never goes
//    backwards.  Requests that move bus signals (local-bus bursts, EPP
//    cycles) take the board time the real bus would take, so now_ns() after
//    them is later than before.
#ifndef VBOARD_BOARD_H
#define VBOARD_BOARD_H

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pins.h"
#include "vboard/proto.h"

namespace vb {

class Board {
  public:
    virtual ~Board() = default;
    Board() = default;
    Board(const Board &) = delete;
    Board &operator=(const Board &) = delete;

    // ---- identity (VB_HELLO) ---------------------------------------------
    virtual std::string name() const = 0;       // "5i20"
    virtual std::string fpga_part() const = 0;  // "2s200pq208"
    virtual uint32_t bus() const = 0;           // enum vb_bus
    virtual std::string firmware() const = 0;   // "" while blank
    bool configured() const { return !firmware().empty(); }
    virtual uint32_t clock_low_hz() const = 0;  // 0 while blank
    virtual uint32_t clock_high_hz() const = 0; // 0 while blank / no 2nd clock
    // Names of the firmwares this build can run on this board.
    virtual std::vector<std::string> firmwares() const = 0;
    // Names of the I/O pins under `firmware` (one entry per pin, in pin
    // order: connector label and module function, either may be empty), so
    // a machine file (vboard --machine) can name pins.  Empty when the
    // firmware is unknown.
    virtual std::vector<std::pair<std::string, std::string>>
    pin_names(const std::string &firmware) const
    {
        (void)firmware;
        return {};
    }

    // ClockLow of one of this build's firmwares for this board (0: unknown),
    // whether it is loaded or not.
    virtual uint32_t firmware_clock_low_hz(const std::string &firmware) const
    {
        (void)firmware;
        return 0;
    }

    // ---- model (vboard --model) -------------------------------------------------
    // Which model runs the firmware: "rtl" (the Verilated firmware, the
    // reference), "fast" (the C++ module models of sim/verilator/fast, proven
    // equal to it by vboard-fastdiff; refused, naming the module, for a
    // firmware with a module they do not cover) or "auto" (fast where the
    // firmware is covered, else rtl).  Applies to the next configuration;
    // `firmware` (may be empty) is checked against the model at once.
    virtual int set_model(const std::string &kind, const std::string &firmware, std::string &err)
    {
        (void)firmware;
        if (kind == "rtl" || kind == "auto")
            return 0;
        err = "board " + name() + " has no fast model (only the hm2 local-bus boards have one); " +
              "use --model rtl";
        return -ENOTSUP;
    }
    // The model running now: "rtl", "fast" or "" while blank.
    virtual std::string model() const { return configured() ? "rtl" : ""; }

    // ---- pins --------------------------------------------------------------
    // The pin layer (levels, external drive, loops, quadrature sources and
    // probe statistics).  Its size never changes over the board's life.
    virtual PinBank &pins() = 0;

    // ---- time --------------------------------------------------------------
    virtual uint64_t now_ns() const = 0;
    // Run the FPGA clocks until board time t_ns (no-op when t_ns <= now).
    // A blank board lets time pass too (pins and quadrature sources move).
    virtual void run_until(uint64_t t_ns) = 0;

    // ---- configuration port (VB_CONFIG) -----------------------------------
    // op is enum vb_config_op; for VB_CONFIG_PROGRAM `bits` is the .BIT
    // file's 'e' chunk (see fwimage.h).  `st` is filled in every case.
    virtual int config(uint32_t op, const uint8_t *bits, size_t len, vb_config_status &st,
                       std::string &err) = 0;
    // Configure with a built-in firmware by name (the command line's
    // --firmware: the board starts configured, no image involved).
    virtual int load(const std::string &firmware, std::string &err) = 0;

    // ---- configuration flash (vboard --flash) -------------------------------
    // Give the board its SPI configuration flash: `path` a file kept in
    // step with the flash ("" = memory only), `part` its type ("" = the
    // board's own), busy times divided by `speedup`.  A new (erased) flash
    // is factory-programmed with `firmware` (boot block, fallback and user
    // image) when that is not empty; then the board configures itself from
    // the flash as at power-up.
    virtual int attach_flash(const std::string &path, const std::string &part, uint32_t speedup,
                             const std::string &firmware, std::string &err)
    {
        (void)path, (void)part, (void)speedup, (void)firmware;
        err = "board " + name() + " has no configuration flash";
        return -ENOTSUP;
    }
    // 1 when the board configures itself from a flash (it then has one
    // from the start, in memory, unless --flash names a file).
    virtual bool flash_configured() const { return false; }

    // ---- hm2 local bus (VB_READ / VB_WRITE) --------------------------------
    // Address/size checks (multiple of 4, inside the 64 KiB window) are done
    // by the server before these are called.  `data` of lb_write holds every
    // xfer's bytes concatenated; lb_read appends every xfer's data to out.
    virtual int lb_read(const vb_xfer *x, size_t n, std::vector<uint8_t> &out, std::string &err)
    {
        (void)x, (void)n, (void)out;
        err = "board " + name() + " has no local bus (it is an EPP board)";
        return -ENOTSUP;
    }
    virtual int lb_write(const vb_xfer *x, size_t n, const uint8_t *data, std::string &err)
    {
        (void)x, (void)n, (void)data;
        err = "board " + name() + " has no local bus (it is an EPP board)";
        return -ENOTSUP;
    }

    // ---- EPP (VB_EPP / VB_EPP_STALL) ----------------------------------------
    // `req` is the raw VB_EPP payload (the board parses it: only it knows its
    // port model); read bytes are appended to out.  A payload that does not
    // parse is -EPROTO with a message.
    virtual int epp(const uint8_t *req, size_t len, std::vector<uint8_t> &out, std::string &err)
    {
        (void)req, (void)len, (void)out;
        err = "board " + name() + " has no EPP port (it is a local-bus board)";
        return -ENOTSUP;
    }
    virtual int epp_stall(bool on, std::string &err)
    {
        (void)on;
        err = "board " + name() + " has no EPP port (it is a local-bus board)";
        return -ENOTSUP;
    }

    // ---- the FPGA's JTAG port (VB_JTAG) ---------------------------------------
    // The lines TCK/TMS/TDI (bits 0..2) now; tdo: the TDO line.
    virtual int jtag(uint32_t levels, uint32_t &tdo, std::string &err)
    {
        (void)levels, (void)tdo;
        err = "board " + name() + " has no JTAG port model";
        return -ENOTSUP;
    }

    // ---- waveforms (VB_DUMP) -------------------------------------------------
    // on: open `path` (.vcd) and trace from now on; off: close the file.
    virtual int dump(bool on, const std::string &path, std::string &err)
    {
        (void)on, (void)path;
        err = "board " + name() + " cannot dump waveforms";
        return -ENOTSUP;
    }
};

// A family of boards.  `boards()` lists the board names it makes;
// `make(board)` returns a blank board (nullptr if the name is not its).
struct BoardFactory {
    std::vector<std::string> (*boards)();
    std::unique_ptr<Board> (*make)(const std::string &board);
};

// The generated table (build: vboard_factories.cpp).
extern const BoardFactory *const kBoardFactories[];
extern const size_t kNumBoardFactories;

// Make a blank board by name; nullptr and a message listing the known
// boards when no factory knows it.
std::unique_ptr<Board> make_board(const std::string &board, std::string &err);

} // namespace vb

#endif // VBOARD_BOARD_H
