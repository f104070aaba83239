// SPDX-License-Identifier: GPL-2.0-or-later
//
// vcd2fst.cpp - VCD to FST through Verilator's FST writer library (fstcpp).
#include "vcd2fst.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <vector>

#ifdef VBOARD_HAVE_FST
#include "fstcpp/fstcpp.h"
#include "fstcpp/fstcpp_writer.h"
#endif

namespace vb {

#ifndef VBOARD_HAVE_FST
bool have_fst() { return false; }

int vcd_to_fst(const std::string &, const std::string &fst, std::string &err)
{
    err = "dump " + fst + ": this vboard was built without FST support (liblz4-dev missing)";
    return -ENOTSUP;
}
#else
bool have_fst() { return true; }

namespace {
int8_t timescale_exp(const std::string &ts)
{
    // "1ps", "10ns", "100us", ...
    size_t i = 0;
    while (i < ts.size() && ts[i] >= '0' && ts[i] <= '9')
        i++;
    int mult = i ? std::stoi(ts.substr(0, i)) : 1;
    std::string unit = ts.substr(i);
    int e = unit == "s" ? 0 : unit == "ms" ? -3 : unit == "us" ? -6 : unit == "ns" ? -9
          : unit == "ps" ? -12 : unit == "fs" ? -15 : -12;
    while (mult >= 10) {
        e++;
        mult /= 10;
    }
    return static_cast<int8_t>(e);
}

struct Sig {
    fst::Handle handle;
    uint32_t width;
};
} // namespace

int vcd_to_fst(const std::string &vcd, const std::string &fst_path, std::string &err)
{
    std::ifstream in(vcd);
    if (!in) {
        err = "dump: cannot read the trace " + vcd + ": " + std::strerror(errno);
        return -EIO;
    }
    std::ofstream probe(fst_path, std::ios::binary);
    if (!probe) {
        err = "dump: cannot open " + fst_path + " for writing";
        return -EIO;
    }
    probe.close();
    fst::Writer w{fst::string_view_pair(fst_path)};
    w.setWriterPackType(fst::WriterPackType::LZ4);
    w.setWriter(fst::string_view_pair("vboard (VCD converted)"));
    std::unordered_map<std::string, Sig> ids;
    std::string tok;
    // Header: whitespace separated tokens up to $enddefinitions.
    while (in >> tok) {
        if (tok == "$enddefinitions") {
            in >> tok; // $end
            break;
        }
        if (tok == "$timescale") {
            std::string ts, t2;
            in >> ts;
            if (ts != "$end" && (in >> t2) && t2 != "$end") // "1 ps" form
                ts += t2, in >> t2;
            w.setTimecale(timescale_exp(ts));
        } else if (tok == "$scope") {
            std::string kind, name, end;
            in >> kind >> name >> end;
            w.setScope(fst::Hierarchy::ScopeType::VCD_MODULE, fst::string_view_pair(name),
                       fst::string_view_pair(""));
        } else if (tok == "$upscope") {
            in >> tok;
            w.upscope();
        } else if (tok == "$var") {
            std::string type, id, name, t;
            uint32_t width = 0;
            in >> type >> width >> id >> name;
            while (in >> t && t != "$end")
                name += t; // [15:0]
            auto it = ids.find(id);
            uint32_t alias = it == ids.end() ? 0 : it->second.handle;
            fst::Handle h = w.createVar(fst::Hierarchy::VarType::VCD_WIRE,
                                        fst::Hierarchy::VarDirection::IMPLICIT, width,
                                        fst::string_view_pair(name), alias);
            if (it == ids.end())
                ids.emplace(id, Sig{h, width});
        } else if (tok[0] == '$') {
            while (tok != "$end" && in >> tok) {
            }
        }
    }
    // Value changes.
    std::string line;
    std::string bits;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '$')
            continue;
        if (line[0] == '#') {
            w.emitTimeChange(std::stoull(line.substr(1)));
            continue;
        }
        std::string val, id;
        if (line[0] == 'b' || line[0] == 'B') {
            size_t sp = line.find(' ');
            if (sp == std::string::npos)
                continue;
            val = line.substr(1, sp - 1);
            id = line.substr(sp + 1);
        } else if (line[0] == 'r' || line[0] == 'R') {
            continue; // no real-valued signals in these models
        } else {
            val = line.substr(0, 1);
            id = line.substr(1);
        }
        auto it = ids.find(id);
        if (it == ids.end())
            continue;
        uint32_t wdt = it->second.width;
        // VCD may drop leading bits: extend with 0 (or x/z when that leads).
        char pad = val.empty() || val[0] == '1' ? '0' : val[0];
        bits.assign(wdt > val.size() ? wdt - val.size() : 0, pad);
        bits += val.size() > wdt ? val.substr(val.size() - wdt) : val;
        w.emitValueChange(it->second.handle, bits.c_str());
    }
    w.close();
    return 0;
}
#endif

} // namespace vb
