// SPDX-License-Identifier: GPL-2.0-or-later
//
// toml.h - a TOML reader for machine files (docs/vboard-machine.md).
//
// It reads the part of TOML 1.0 a configuration needs: comments, bare,
// quoted and dotted keys, [tables], [[arrays of tables]], basic and literal
// strings (one line), integers (decimal, 0x hex, _ separators), floats
// (including inf and nan), booleans, arrays (over several lines, trailing
// comma) and inline tables.  Dates and multi-line strings are refused with
// an error.  Every value remembers its line, so the checks of a machine
// file name file:line and the key.
#ifndef VBOARD_PLANT_TOML_H
#define VBOARD_PLANT_TOML_H

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace vb::plant::toml {

struct Value {
    enum class Type { String, Integer, Float, Bool, Array, Table };
    Type type = Type::Table;
    int line = 0;
    std::string str;
    int64_t integer = 0;
    double number = 0;
    bool boolean = false;
    std::vector<Value> array;
    std::vector<std::pair<std::string, Value>> table; // in file order
    bool inline_table = false;     // { ... }: closed, no later additions
    bool array_of_tables = false;  // made by [[...]]
    bool defined = false;          // table defined by a [header] already

    bool is_number() const { return type == Type::Integer || type == Type::Float; }
    double as_double() const { return type == Type::Integer ? static_cast<double>(integer) : number; }
    const Value *find(const std::string &key) const;
    Value *find(const std::string &key);
};

const char *type_name(Value::Type t);

// Parse `text` (the contents of file `path`, used in messages).  On error
// returns false with "path:line: what" in err.
bool parse(const std::string &text, const std::string &path, Value &root, std::string &err);

} // namespace vb::plant::toml

#endif // VBOARD_PLANT_TOML_H
