// SPDX-License-Identifier: GPL-2.0-or-later
//
// fstcpp_impl.cpp - compiles Verilator's FST writer library (fstcpp, part
// of the Verilator runtime) once for vcd2fst.cpp.  Third-party code: built
// without our warning flags.
#include "fstcpp/fstcpp_variable_info.cpp"
#include "fstcpp/fstcpp_writer.cpp"
