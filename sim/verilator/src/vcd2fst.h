// SPDX-License-Identifier: GPL-2.0-or-later
//
// vcd2fst.h - convert a VCD file (as Verilator's VerilatedVcdC writes it)
// into FST.  Verilator compiles one trace format into a model; the vboard's
// models trace VCD, and an .fst dump is a VCD converted when it is closed.
#ifndef VBOARD_VCD2FST_H
#define VBOARD_VCD2FST_H

#include <string>

namespace vb {

// True when this build can write FST (the FST writer needs liblz4).
bool have_fst();

// Convert; 0, or -errno with the reason in err (the FST file may then be
// incomplete).
int vcd_to_fst(const std::string &vcd, const std::string &fst, std::string &err);

} // namespace vb

#endif // VBOARD_VCD2FST_H
