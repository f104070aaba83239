// SPDX-License-Identifier: GPL-2.0-or-later
//
// fast_model.h - the fast model of an hm2 local-bus firmware: the same
// clocks, bus timing and pin behaviour as the Verilated firmware
// (localbus_model.h, the reference), from C++ models of its modules
// (fast_modules.h) configured by the firmware's IDROM (fast_config.h).
//
// Time.  ClockHigh edge k is at k*Th after the model started, ClockLow's on
// every R-th of them, exactly as in LbModel (and ClockLow edges only when no
// module uses ClockHigh).  Every edge the model executes calls the pin layer
// like LbModel does (run_events before, set_fpga after).  Between requests
// and pin events, while every module is in a steady state, the model lets
// whole ClockLow cycles pass in closed form: as many as every module's
// horizon allows, none past the next pin event or the requested time.
// Those edges would change no pin, so the pin layer sees the same history.
#ifndef VBOARD_FAST_MODEL_H
#define VBOARD_FAST_MODEL_H

#include <memory>
#include <string>

#include "fwinfo.h"
#include "localbus.h"
#include "pins.h"

namespace vb::fast {

// A fast model of firmware `info` whose IDROM is `idrom` (256 words), at
// board time `start`, wired to `pins`; nullptr and the reason (naming the
// first module it does not cover) when it cannot model the firmware.
std::unique_ptr<LbModelBase> make_fast_model(const FwInfo &info, const uint32_t *idrom,
                                             PinBank &pins, uint64_t start, std::string &err);

// Whether the fast model covers firmware `idrom`; "" or the reason.
std::string fast_coverage(const uint32_t *idrom);

// Statistics of a fast model (tests and benchmarks): ClockHigh edges
// executed one by one and let pass in closed form.
struct FastStats {
    uint64_t stepped = 0, skipped = 0;
};
FastStats fast_stats(const LbModelBase &m);

} // namespace vb::fast

#endif // VBOARD_FAST_MODEL_H
