// SPDX-License-Identifier: GPL-2.0-or-later
//
// toml.cpp - the machine files' TOML reader (toml.h).
#include "toml.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace vb::plant::toml {

const Value *Value::find(const std::string &key) const
{
    for (const auto &kv : table)
        if (kv.first == key)
            return &kv.second;
    return nullptr;
}

Value *Value::find(const std::string &key)
{
    for (auto &kv : table)
        if (kv.first == key)
            return &kv.second;
    return nullptr;
}

const char *type_name(Value::Type t)
{
    switch (t) {
    case Value::Type::String: return "a string";
    case Value::Type::Integer: return "an integer";
    case Value::Type::Float: return "a float";
    case Value::Type::Bool: return "a boolean";
    case Value::Type::Array: return "an array";
    case Value::Type::Table: return "a table";
    }
    return "?";
}

namespace {

class Parser {
  public:
    Parser(const std::string &text, const std::string &path) : s_(text), path_(path) {}

    bool run(Value &root)
    {
        root = Value{};
        root.type = Value::Type::Table;
        root.line = 1;
        Value *cur = &root;
        while (skip_blank_lines()) {
            if (peek() == '[') {
                cur = header(root);
                if (!cur)
                    return false;
            } else if (!key_value(*cur)) {
                return false;
            }
            if (!end_of_line())
                return false;
        }
        return true;
    }

    std::string err;

  private:
    char peek(size_t k = 0) const { return pos_ + k < s_.size() ? s_[pos_ + k] : '\0'; }
    bool at_end() const { return pos_ >= s_.size(); }

    bool fail(const std::string &what)
    {
        err = path_ + ":" + std::to_string(line_) + ": " + what;
        return false;
    }

    void skip_ws()
    {
        while (peek() == ' ' || peek() == '\t')
            pos_++;
    }
    void skip_comment()
    {
        if (peek() == '#')
            while (!at_end() && peek() != '\n')
                pos_++;
    }
    // Skips blank and comment lines; false at the end of the text.
    bool skip_blank_lines()
    {
        for (;;) {
            skip_ws();
            skip_comment();
            if (peek() == '\r' && peek(1) == '\n')
                pos_++;
            if (peek() == '\n') {
                pos_++;
                line_++;
                continue;
            }
            return !at_end();
        }
    }
    // Whitespace/comment and a newline (or the end) after an expression.
    bool end_of_line()
    {
        skip_ws();
        skip_comment();
        if (peek() == '\r' && peek(1) == '\n')
            pos_++;
        if (at_end())
            return true;
        if (peek() != '\n')
            return fail(std::string("unexpected '") + peek() + "' after the value");
        pos_++;
        line_++;
        return true;
    }
    // Inside arrays: whitespace, comments and newlines.
    void skip_ws_nl()
    {
        for (;;) {
            skip_ws();
            skip_comment();
            if (peek() == '\r' && peek(1) == '\n')
                pos_++;
            if (peek() != '\n')
                return;
            pos_++;
            line_++;
        }
    }

    static bool bare_char(char c)
    {
        return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
               c == '_' || c == '-';
    }

    bool key_part(std::string &k)
    {
        skip_ws();
        if (peek() == '"' || peek() == '\'') {
            Value v;
            if (!string_value(v))
                return false;
            k = v.str;
        } else {
            size_t start = pos_;
            while (bare_char(peek()))
                pos_++;
            if (pos_ == start)
                return fail(peek() == '\n' || at_end()
                                ? std::string("a key is missing")
                                : std::string("'") + peek() + "' cannot start a key");
            k = s_.substr(start, pos_ - start);
        }
        skip_ws();
        return true;
    }

    bool dotted_key(std::vector<std::string> &keys)
    {
        keys.clear();
        for (;;) {
            std::string k;
            if (!key_part(k))
                return false;
            keys.push_back(k);
            if (peek() != '.')
                return true;
            pos_++;
        }
    }

    static std::string join(const std::vector<std::string> &keys, size_t n)
    {
        std::string out;
        for (size_t i = 0; i < n && i < keys.size(); i++)
            out += (i ? "." : "") + keys[i];
        return out;
    }

    // Descend into (creating) the table at keys[0..n) from t.  Arrays of
    // tables descend into their last element.
    Value *descend(Value *t, const std::vector<std::string> &keys, size_t n)
    {
        for (size_t i = 0; i < n; i++) {
            Value *next = t->find(keys[i]);
            if (!next) {
                Value v;
                v.type = Value::Type::Table;
                v.line = line_;
                t->table.emplace_back(keys[i], std::move(v));
                next = &t->table.back().second;
            } else if (next->type == Value::Type::Array && next->array_of_tables) {
                next = &next->array.back();
            } else if (next->type != Value::Type::Table || next->inline_table) {
                fail("key '" + join(keys, i + 1) + "' is already " + type_name(next->type) +
                     " (line " + std::to_string(next->line) + "), not a table");
                return nullptr;
            }
            t = next;
        }
        return t;
    }

    Value *header(Value &root)
    {
        pos_++; // [
        bool aot = peek() == '[';
        if (aot)
            pos_++;
        std::vector<std::string> keys;
        if (!dotted_key(keys))
            return nullptr;
        if (peek() != ']' || (aot && peek(1) != ']')) {
            fail(std::string("table header [") + (aot ? "[" : "") + join(keys, keys.size()) +
                 " is not closed by ']" + (aot ? "]'" : "'"));
            return nullptr;
        }
        pos_ += aot ? 2 : 1;
        Value *parent = descend(&root, keys, keys.size() - 1);
        if (!parent)
            return nullptr;
        const std::string &last = keys.back();
        Value *t = parent->find(last);
        if (aot) {
            if (!t) {
                Value a;
                a.type = Value::Type::Array;
                a.array_of_tables = true;
                a.line = line_;
                parent->table.emplace_back(last, std::move(a));
                t = &parent->table.back().second;
            } else if (t->type != Value::Type::Array || !t->array_of_tables) {
                fail("[[" + join(keys, keys.size()) + "]]: the key is already " +
                     type_name(t->type) + " (line " + std::to_string(t->line) + ")");
                return nullptr;
            }
            Value e;
            e.type = Value::Type::Table;
            e.line = line_;
            e.defined = true;
            t->array.push_back(std::move(e));
            return &t->array.back();
        }
        if (!t) {
            Value v;
            v.type = Value::Type::Table;
            v.line = line_;
            parent->table.emplace_back(last, std::move(v));
            t = &parent->table.back().second;
        } else if (t->type != Value::Type::Table || t->inline_table) {
            fail("[" + join(keys, keys.size()) + "]: the key is already " + type_name(t->type) +
                 " (line " + std::to_string(t->line) + ")");
            return nullptr;
        } else if (t->defined) {
            fail("table [" + join(keys, keys.size()) + "] is defined twice (first on line " +
                 std::to_string(t->line) + ")");
            return nullptr;
        }
        t->defined = true;
        t->line = line_;
        return t;
    }

    bool key_value(Value &table)
    {
        std::vector<std::string> keys;
        if (!dotted_key(keys))
            return false;
        if (peek() != '=')
            return fail("expected '=' after key '" + join(keys, keys.size()) + "'");
        pos_++;
        skip_ws();
        Value v;
        if (!value(v))
            return false;
        Value *t = descend(&table, keys, keys.size() - 1);
        if (!t)
            return false;
        if (const Value *old = t->find(keys.back()))
            return fail("key '" + join(keys, keys.size()) + "' is defined twice (first on line " +
                        std::to_string(old->line) + ")");
        t->table.emplace_back(keys.back(), std::move(v));
        return true;
    }

    bool value(Value &v)
    {
        v = Value{};
        v.line = line_;
        char c = peek();
        if (c == '"' || c == '\'')
            return string_value(v);
        if (c == '[')
            return array_value(v);
        if (c == '{')
            return inline_table(v);
        if (s_.compare(pos_, 4, "true") == 0 && !bare_char(peek(4))) {
            pos_ += 4;
            v.type = Value::Type::Bool;
            v.boolean = true;
            return true;
        }
        if (s_.compare(pos_, 5, "false") == 0 && !bare_char(peek(5))) {
            pos_ += 5;
            v.type = Value::Type::Bool;
            return true;
        }
        return number_value(v);
    }

    bool string_value(Value &v)
    {
        char q = peek();
        if (peek(1) == q && peek(2) == q)
            return fail("multi-line strings are not supported in machine files");
        pos_++;
        v.type = Value::Type::String;
        v.line = line_;
        std::string out;
        for (;;) {
            char c = peek();
            if (at_end() || c == '\n')
                return fail("string is not closed on its line");
            pos_++;
            if (c == q)
                break;
            if (c == '\\' && q == '"') {
                char e = peek();
                pos_++;
                switch (e) {
                case '"': out += '"'; break;
                case '\\': out += '\\'; break;
                case 'n': out += '\n'; break;
                case 't': out += '\t'; break;
                case 'r': out += '\r'; break;
                default: return fail(std::string("unknown escape '\\") + e + "' in a string");
                }
                continue;
            }
            out += c;
        }
        v.str = out;
        return true;
    }

    bool array_value(Value &v)
    {
        pos_++;
        v.type = Value::Type::Array;
        int start = line_;
        for (;;) {
            skip_ws_nl();
            if (peek() == ']') {
                pos_++;
                return true;
            }
            if (at_end())
                return fail("array opened on line " + std::to_string(start) + " is not closed");
            Value e;
            if (!value(e))
                return false;
            v.array.push_back(std::move(e));
            skip_ws_nl();
            if (peek() == ',') {
                pos_++;
                continue;
            }
            if (peek() != ']')
                return fail("expected ',' or ']' in the array opened on line " +
                            std::to_string(start));
        }
    }

    bool inline_table(Value &v)
    {
        pos_++;
        v.type = Value::Type::Table;
        v.inline_table = true;
        skip_ws();
        if (peek() == '}') {
            pos_++;
            return true;
        }
        for (;;) {
            if (!key_value(v))
                return false;
            skip_ws();
            if (peek() == ',') {
                pos_++;
                continue;
            }
            if (peek() == '}') {
                pos_++;
                return true;
            }
            return fail("expected ',' or '}' in an inline table (it must fit on one line)");
        }
    }

    bool number_value(Value &v)
    {
        size_t start = pos_;
        while (bare_char(peek()) || peek() == '+' || peek() == '.' || peek() == ':')
            pos_++;
        std::string tok = s_.substr(start, pos_ - start);
        if (tok.empty())
            return fail(at_end() || peek() == '\n' ? std::string("a value is missing")
                                                   : std::string("'") + peek() +
                                                         "' cannot start a value");
        std::string t;
        for (size_t i = 0; i < tok.size(); i++) {
            if (tok[i] == '_') {
                bool ok = i > 0 && i + 1 < tok.size() && std::isxdigit((unsigned char)tok[i - 1]) &&
                          std::isxdigit((unsigned char)tok[i + 1]);
                if (!ok)
                    return fail("'" + tok + "' is not a number (misplaced '_')");
                continue;
            }
            t += tok[i];
        }
        std::string body = (t[0] == '+' || t[0] == '-') ? t.substr(1) : t;
        if (body == "inf" || body == "nan") {
            v.type = Value::Type::Float;
            v.number = body == "inf" ? INFINITY : NAN;
            if (t[0] == '-')
                v.number = -v.number;
            return true;
        }
        if (body.empty() || (!std::isdigit((unsigned char)body[0]) && body[0] != '.'))
            return fail("'" + tok + "' is not a value (strings need quotes)");
        if (t.find(':') != std::string::npos || (t.size() > 4 && t[4] == '-' && std::isdigit((unsigned char)t[0]) &&
                                                  std::isdigit((unsigned char)t[3])))
            return fail("'" + tok + "': dates and times are not supported in machine files");
        errno = 0;
        char *end = nullptr;
        if (body.size() > 2 && body[0] == '0' && (body[1] == 'x' || body[1] == 'X')) {
            unsigned long long x = std::strtoull(body.c_str() + 2, &end, 16);
            if (*end || errno || x > INT64_MAX || t[0] == '-' || t[0] == '+')
                return fail("'" + tok + "' is not a valid hexadecimal integer");
            v.type = Value::Type::Integer;
            v.integer = static_cast<int64_t>(x);
            return true;
        }
        bool is_float = t.find_first_of(".eE") != std::string::npos;
        if (!is_float) {
            if (body.size() > 1 && body[0] == '0')
                return fail("'" + tok + "': integers have no leading zeros");
            long long x = std::strtoll(t.c_str(), &end, 10);
            if (*end || errno || t.empty())
                return fail("'" + tok + "' is not a value (strings need quotes)");
            v.type = Value::Type::Integer;
            v.integer = x;
            return true;
        }
        double d = std::strtod(t.c_str(), &end);
        if (*end || errno == ERANGE || body.empty() || !std::isdigit((unsigned char)body[0]) ||
            !std::isdigit((unsigned char)t.back()))
            return fail("'" + tok + "' is not a valid number");
        v.type = Value::Type::Float;
        v.number = d;
        return true;
    }

    const std::string &s_;
    std::string path_;
    size_t pos_ = 0;
    int line_ = 1;
};

} // namespace

bool parse(const std::string &text, const std::string &path, Value &root, std::string &err)
{
    Parser p(text, path);
    Value r;
    if (!p.run(r)) {
        err = p.err;
        return false;
    }
    root = std::move(r);
    return true;
}

} // namespace vb::plant::toml
